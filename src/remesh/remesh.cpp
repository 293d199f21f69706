#include "meander/remesh.h"

#include "core/union_find.h"
#include "meander/check.h"
#include "meander/coarsen.h"
#include "meander/connectivity.h"
#include "meander/error.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

namespace meander {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// An orientable mesh made of the input by cutting its non-orientable components along a
// seam, with what is needed to glue them back.
struct CutMesh {
  PolygonMesh mesh;
  std::vector<int32_t> original; // per vertex: the vertex it copies (itself if none); empty if nothing was cut
  std::vector<uint8_t> was_cut;  // per vertex: of a component cut open; empty if none was
};

// Faces oriented by a search across edges, each face agreeing with the one it was reached
// from; the edges where two faces still disagree are the seam of a non-orientable
// component. On an orientable mesh, whose faces repair() made agree, nothing is flipped.
struct Orientation {
  std::vector<uint8_t> flip;      // per face
  std::vector<int32_t> component; // per face
  std::vector<uint8_t> seam;      // per edge
  std::vector<uint8_t> cut;       // per component: it has a seam
};

Orientation orient(const PolygonMesh& mesh, const Connectivity& c) {
  const int32_t faces = mesh.num_faces();
  Orientation o{.flip = std::vector<uint8_t>(size_t(faces), 0),
                .component = std::vector<int32_t>(size_t(faces), -1),
                .seam = std::vector<uint8_t>(size_t(c.num_edges()), 0)};
  // Whether halfedge h runs from the lower vertex of its edge to the higher, its face
  // flipped or not.
  auto forward = [&](int32_t h) {
    return (mesh.face_vertices[size_t(h)] == c.edge_vertices[size_t(c.halfedge_edge[size_t(h)])][0]) !=
           bool(o.flip[size_t(c.face_of(h))]);
  };
  std::vector<int32_t> queue;
  for (int32_t root = 0; root < faces; ++root) {
    if (o.component[size_t(root)] >= 0) continue;
    const int32_t k = int32_t(o.cut.size());
    o.cut.push_back(0);
    o.component[size_t(root)] = k;
    queue.assign(1, root);
    for (size_t next = 0; next < queue.size(); ++next) {
      const int32_t f = queue[next];
      for (int32_t h = mesh.face_start[size_t(f)]; h < mesh.face_start[size_t(f) + 1]; ++h) {
        const int32_t e = c.halfedge_edge[size_t(h)];
        if (c.edge_degree(e) != 2) continue;
        const std::span<const int32_t> pair = c.halfedges(e);
        const int32_t other = pair[0] == h ? pair[1] : pair[0], g = c.face_of(other);
        if (o.component[size_t(g)] < 0) {
          o.component[size_t(g)] = k;
          o.flip[size_t(g)] =
              uint8_t((mesh.face_vertices[size_t(other)] == c.edge_vertices[size_t(e)][0]) == forward(h));
          queue.push_back(g);
        } else if (forward(h) == forward(other)) {
          o.seam[size_t(e)] = 1;
          o.cut[size_t(k)] = 1;
        }
      }
    }
  }
  return o;
}

// The mesh with its non-orientable components cut open along their seams, each vertex on
// a seam copied once per side. CGAL then keeps the boundary edges of those components as
// they are (protected), so that the two sides of a seam stay alike: these edges are split
// first into pieces no longer than `longest`, at the same points on both sides.
CutMesh cut_open(const PolygonMesh& mesh, double longest) {
  const Connectivity c = build_connectivity(mesh);
  const Orientation o = orient(mesh, c);
  CutMesh cut;
  if (std::find(o.cut.begin(), o.cut.end(), 1) == o.cut.end()) {
    cut.mesh = mesh;
    return cut;
  }
  // Faces flipped as oriented, the points of each split edge inserted where it runs.
  PolygonMesh& m = cut.mesh;
  m.positions = mesh.positions;
  std::vector<int32_t> edge_points(size_t(c.num_edges()) + 1,
                                   0); // the first point added on edge e
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    int32_t pieces = 1;
    const bool kept = o.seam[size_t(e)] ||
                      (c.edge_degree(e) == 1 && o.cut[size_t(o.component[size_t(c.face_of(c.halfedges(e)[0]))])]);
    if (kept) {
      const Vec3 a = mesh.positions[size_t(c.edge_vertices[size_t(e)][0])],
                 b = mesh.positions[size_t(c.edge_vertices[size_t(e)][1])];
      pieces = std::max(1, int32_t(std::ceil(norm(b - a) / longest)));
      for (int32_t k = 1; k < pieces; ++k) m.positions.push_back(a + (b - a) * (float(k) / float(pieces)));
    }
    edge_points[size_t(e) + 1] = edge_points[size_t(e)] + pieces - 1;
  }
  std::vector<std::array<int32_t, 2>> seam_pieces;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const int32_t begin = mesh.face_start[size_t(f)], end = mesh.face_start[size_t(f) + 1];
    const size_t face_begin = m.face_vertices.size();
    for (int32_t h = begin; h < end; ++h) {
      const int32_t e = c.halfedge_edge[size_t(h)], from = mesh.face_vertices[size_t(h)];
      const int32_t added = edge_points[size_t(e) + 1] - edge_points[size_t(e)];
      const bool from_low = from == c.edge_vertices[size_t(e)][0];
      int32_t previous = from;
      m.face_vertices.push_back(from);
      for (int32_t k = 0; k < added; ++k) {
        const int32_t v = mesh.num_vertices() + edge_points[size_t(e)] + (from_low ? k : added - 1 - k);
        m.face_vertices.push_back(v);
        if (o.seam[size_t(e)]) seam_pieces.push_back({std::min(previous, v), std::max(previous, v)});
        previous = v;
      }
      const int32_t to = mesh.face_vertices[size_t(h + 1 == end ? begin : h + 1)];
      if (o.seam[size_t(e)]) seam_pieces.push_back({std::min(previous, to), std::max(previous, to)});
    }
    if (o.flip[size_t(f)]) std::reverse(m.face_vertices.begin() + ptrdiff_t(face_begin), m.face_vertices.end());
    m.face_start.push_back(int32_t(m.face_vertices.size()));
  }
  // Each vertex gets a copy per fan of its corners joined across edges off the seam.
  const Connectivity split = build_connectivity(m);
  std::vector<uint8_t> is_seam(size_t(split.num_edges()), 0);
  for (const std::array<int32_t, 2>& key : seam_pieces)
    is_seam[size_t(std::lower_bound(split.edge_vertices.begin(), split.edge_vertices.end(), key) -
                   split.edge_vertices.begin())] = 1;
  UnionFind fans(m.num_corners());
  for (int32_t e = 0; e < split.num_edges(); ++e) {
    if (split.edge_degree(e) != 2 || is_seam[size_t(e)]) continue;
    const int32_t h1 = split.halfedges(e)[0], h2 = split.halfedges(e)[1];
    fans.unite(h1, next_halfedge(m, split, h2));
    fans.unite(next_halfedge(m, split, h1), h2);
  }
  cut.original.resize(m.positions.size());
  for (size_t v = 0; v < cut.original.size(); ++v) cut.original[v] = int32_t(v);
  std::vector<int32_t> fan_vertex(size_t(m.num_corners()), -1);
  std::vector<uint8_t> taken(m.positions.size(), 0);
  for (int32_t h = 0; h < m.num_corners(); ++h) {
    const int32_t v = m.face_vertices[size_t(h)], fan = fans.find(h);
    if (fan_vertex[size_t(fan)] < 0) {
      if (!taken[size_t(v)]) {
        taken[size_t(v)] = 1;
        fan_vertex[size_t(fan)] = v;
      } else {
        fan_vertex[size_t(fan)] = m.num_vertices();
        m.positions.push_back(m.positions[size_t(v)]);
        cut.original.push_back(v);
      }
    }
    m.face_vertices[size_t(h)] = fan_vertex[size_t(fan)];
  }
  cut.was_cut.resize(m.positions.size());
  for (int32_t f = 0; f < m.num_faces(); ++f)
    for (int32_t v : m.face(f)) cut.was_cut[size_t(v)] = o.cut[size_t(o.component[size_t(f)])];
  return cut;
}

// The topology remeshing must keep: per component (Euler characteristic, boundary loops,
// orientable), sorted.
using Topology = std::vector<std::tuple<int64_t, int32_t, bool>>;
Topology topology(const PolygonMesh& mesh) {
  const MeshReport report = inspect(mesh);
  Topology components;
  for (const ComponentReport& c : report.components)
    components.emplace_back(c.euler_characteristic, c.boundary_loops, c.orientable);
  std::sort(components.begin(), components.end());
  return components;
}

std::string describe(const Topology& components) {
  std::string text = std::to_string(components.size()) + " component" + (components.size() == 1 ? "" : "s");
  int64_t euler = 0, loops = 0;
  for (const auto& [chi, b, orientable] : components) euler += chi, loops += b;
  return text + ", Euler characteristic " + std::to_string(euler) + ", " + std::to_string(loops) + " boundary loop" +
         (loops == 1 ? "" : "s");
}

// Edges shorter than this fraction of the target are collapsed before CGAL remeshes a
// fine input, leaving about 5 times the faces of the result. CGAL's time falls with it
// (a 1M-triangle sphere at 1/200 of its diagonal: 1.0 s at 0.3, 0.28 s at 0.45), and the
// evenness of the curve made on the result changes with it, though not in order: at
// 0.3, 0.35 and 0.45 one or two real meshes came out just over the CV target of
// spacing_test.cpp (0.125 to 0.128 against 0.12), at 0.6 to 1.0 the kitten at 1/30 too.
constexpr double kCoarse = 0.4;

void check_edge_length(double length) {
  if (!(length > 0) || !std::isfinite(length))
    throw ParameterError("edge_length", " must be a positive number (got " + std::to_string(length) + ")");
}

} // namespace

double surface_area(const PolygonMesh& mesh) {
  double area = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> face = mesh.face(f);
    const Vec3d first = to_double(mesh.positions[size_t(face[0])]);
    for (size_t i = 1; i + 1 < face.size(); ++i)
      area += 0.5 * norm(cross(to_double(mesh.positions[size_t(face[i])]) - first,
                               to_double(mesh.positions[size_t(face[i + 1])]) - first));
  }
  return area;
}

int64_t remeshed_faces_estimate(const PolygonMesh& mesh, double edge_length) {
  // CGAL keeps edges between 4/5 and 4/3 of the target, most of them shorter: measured,
  // 1.1 to 1.36 times as many faces as equilateral triangles of the target's side.
  constexpr double measured = 1.4;
  const double faces = measured * surface_area(mesh) / (std::sqrt(3.0) / 4 * edge_length * edge_length);
  return faces < 9e18 ? int64_t(std::ceil(faces)) : INT64_MAX;
}

PolygonMesh remesh(const PolygonMesh& mesh, const RemeshOptions& options) {
  check_edge_length(options.edge_length); // before the tree is built
  return remesh(mesh, options, ClosestPoints(mesh));
}

PolygonMesh remesh(const PolygonMesh& mesh, const RemeshOptions& options, const ClosestPoints& input) {
  const double length = options.edge_length;
  check_edge_length(length);
  const int64_t estimate = remeshed_faces_estimate(mesh, length);
  if (options.max_faces > 0 && estimate > options.max_faces)
    throw InputError("the remeshed surface would have about " + std::to_string(estimate) + " faces, over the limit of " +
                     std::to_string(options.max_faces) + ": choose a larger spacing");
  const Topology before = topology(mesh);
  // A triangle mesh of more than 8 times the faces of the result is coarsened first:
  // CGAL's remeshing then starts from fewer, and the projection onto the input restores
  // the shape. CGAL keeps protected edges no longer than 4/3 of the target.
  const bool fine = mesh.face_vertices.size() == 3 * size_t(mesh.num_faces()) && mesh.num_faces() > 8 * estimate;
  const CutMesh cut = cut_open(fine ? coarsen(mesh, kCoarse * length) : mesh, length * 4 / 3);
  const PolygonMesh& open = cut.mesh;
  auto copy_of = [&cut](int32_t v) { return cut.original.empty() ? v : cut.original[size_t(v)]; };

  SurfaceMesh surface;
  auto origin = surface.add_property_map<SurfaceMesh::Vertex_index, int32_t>("v:origin", -1).first;
  std::vector<SurfaceMesh::Vertex_index> vertex(open.positions.size());
  for (size_t v = 0; v < open.positions.size(); ++v) {
    const Vec3 p = open.positions[v];
    vertex[v] = surface.add_vertex({p.x, p.y, p.z});
    origin[vertex[v]] = int32_t(v);
  }
  std::vector<SurfaceMesh::Vertex_index> corners;
  for (int32_t f = 0; f < open.num_faces(); ++f) {
    corners.clear();
    for (int32_t v : open.face(f)) corners.push_back(vertex[size_t(v)]);
    if (surface.add_face(corners) == SurfaceMesh::null_face())
      throw TopologyError("remeshing: face " + std::to_string(f) + " does not fit an oriented manifold surface");
  }
  if (!PMP::triangulate_faces(surface))
    throw TopologyError("remeshing: a polygon of the mesh could not be triangulated (degenerate)");
  // Faces whose corners lie on a line go first (collapsed or flipped away; the topology
  // is checked below): CGAL 5.5's tangential relaxation crashes at a vertex all of whose
  // faces are such (CGAL issue 7345), as splitting one along a fine spacing makes.
  PMP::remove_degenerate_faces(surface);
  surface.collect_garbage();
  std::vector<SurfaceMesh::Face_index> whole, opened;
  for (SurfaceMesh::Face_index f : surface.faces()) {
    const int32_t v = origin[surface.target(surface.halfedge(f))];
    (!cut.was_cut.empty() && cut.was_cut[size_t(v)] ? opened : whole).push_back(f);
  }
  // Every vertex made or moved goes onto the input surface, not the coarsened one.
  const auto onto_input = [&](SurfaceMesh::Vertex_index v) {
    const auto& p = surface.point(v);
    const Vec3d q = input.closest({p.x(), p.y(), p.z()});
    return Kernel::Point_3(q.x, q.y, q.z);
  };
  const auto np = CGAL::parameters::number_of_iterations(unsigned(options.iterations)).projection_functor(onto_input);
  // Orientable components: boundaries split and collapsed like the rest. Components cut
  // open: their boundary (seam included) kept, so that the seam's sides still match.
  PMP::isotropic_remeshing(whole, length, surface, np);
  PMP::isotropic_remeshing(opened, length, surface, np.protect_constraints(true));

  // Back to a polygon mesh, the two sides of each seam glued into one vertex again.
  PolygonMesh result;
  std::vector<int32_t> index(surface.num_vertices() + surface.number_of_removed_vertices(), -1);
  std::vector<int32_t> glued(open.positions.size(), -1);
  for (SurfaceMesh::Vertex_index v : surface.vertices()) {
    const int32_t from = origin[v];
    if (from >= 0 && copy_of(from) != from) continue; // a copy: glued to its original below
    index[v.idx()] = result.num_vertices();
    if (from >= 0) glued[size_t(from)] = result.num_vertices();
    const auto& p = surface.point(v);
    result.positions.push_back({float(p.x()), float(p.y()), float(p.z())});
  }
  for (SurfaceMesh::Vertex_index v : surface.vertices())
    if (const int32_t from = origin[v]; from >= 0 && copy_of(from) != from)
      index[v.idx()] = glued[size_t(copy_of(from))];
  for (SurfaceMesh::Face_index f : surface.faces()) {
    for (SurfaceMesh::Vertex_index v : surface.vertices_around_face(surface.halfedge(f))) {
      if (index[v.idx()] < 0) throw TopologyError("remeshing: the seam of a non-orientable component lost a vertex");
      result.face_vertices.push_back(index[v.idx()]);
    }
    result.face_start.push_back(int32_t(result.face_vertices.size()));
  }
  if (const Topology after = topology(result); before != after)
    throw TopologyError("remeshing at edge length " + std::to_string(length) + " changed the surface's topology (" +
                        describe(before) + " before, " + describe(after) +
                        " after): a part is thinner than the spacing; choose a smaller spacing");
  return result;
}

} // namespace meander
