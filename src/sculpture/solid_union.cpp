#include "meander/solid_union.h"

#include "meander/error.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

namespace meander {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// The mesh as a Surface_mesh of triangles (quads cut by CGAL's fixed rule, the flatter
// diagonal); `name` for the messages.
SurfaceMesh to_surface(const PolygonMesh& mesh, std::string_view name) {
  SurfaceMesh surface;
  std::vector<SurfaceMesh::Vertex_index> vertex;
  vertex.reserve(mesh.positions.size());
  for (const Vec3 p : mesh.positions) vertex.push_back(surface.add_vertex({p.x, p.y, p.z}));
  std::vector<SurfaceMesh::Vertex_index> corners;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    corners.clear();
    for (int32_t v : mesh.face(f)) corners.push_back(vertex[size_t(v)]);
    if (mesh.face(f).size() > 4)
      throw InputError("union: the " + std::string(name) + "'s face " + std::to_string(f) +
                       " has more than four corners (triangles and quads only)");
    if (surface.add_face(corners) == SurfaceMesh::null_face())
      throw InputError("union: the " + std::string(name) + "'s face " + std::to_string(f) +
                       " does not fit an oriented manifold surface");
  }
  PMP::triangulate_faces(surface);
  return surface;
}

SurfaceMesh solid(const PolygonMesh& mesh, std::string_view name) {
  SurfaceMesh surface = to_surface(mesh, name);
  if (!CGAL::is_closed(surface)) throw InputError("union: the " + std::string(name) + " is not closed");
  if (PMP::does_self_intersect(surface)) throw InputError("union: the " + std::string(name) + " intersects itself");
  return surface;
}

PolygonMesh to_polygons(const SurfaceMesh& surface) {
  PolygonMesh mesh;
  std::vector<int32_t> index(surface.num_vertices() + surface.number_of_removed_vertices(), -1);
  for (SurfaceMesh::Vertex_index v : surface.vertices()) {
    index[v.idx()] = mesh.num_vertices();
    const auto& p = surface.point(v);
    mesh.positions.push_back({float(p.x()), float(p.y()), float(p.z())});
  }
  for (SurfaceMesh::Face_index f : surface.faces()) {
    for (SurfaceMesh::Vertex_index v : surface.vertices_around_face(surface.halfedge(f)))
      mesh.face_vertices.push_back(index[v.idx()]);
    mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
  }
  return mesh;
}

// CGAL's corefinement numbers the union's vertices and faces in an order that follows
// heap addresses (the same surface came out numbered otherwise with -v on the command
// line): renumbered here from the geometry alone, faces (triangles) by their corners' positions
// (each face rotated to start at its least, so its orientation stays), vertices as the
// faces first meet them.
PolygonMesh in_order_of_positions(const PolygonMesh& mesh) {
  const auto less = [](Vec3 a, Vec3 b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  std::vector<std::array<int32_t, 3>> faces(size_t(mesh.num_faces()));
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> c = mesh.face(f);
    size_t first = 0;
    for (size_t k = 1; k < 3; ++k)
      if (less(mesh.positions[size_t(c[k])], mesh.positions[size_t(c[first])])) first = k;
    faces[size_t(f)] = {c[first], c[(first + 1) % 3], c[(first + 2) % 3]};
  }
  std::sort(faces.begin(), faces.end(), [&](const auto& a, const auto& b) {
    for (size_t k = 0; k < 3; ++k) {
      const Vec3 p = mesh.positions[size_t(a[k])], q = mesh.positions[size_t(b[k])];
      if (less(p, q)) return true;
      if (less(q, p)) return false;
    }
    return false;
  });
  PolygonMesh result;
  std::vector<int32_t> index(mesh.positions.size(), -1);
  for (const auto& face : faces) {
    for (int32_t v : face) {
      if (index[size_t(v)] < 0) {
        index[size_t(v)] = result.num_vertices();
        result.positions.push_back(mesh.positions[size_t(v)]);
      }
      result.face_vertices.push_back(index[size_t(v)]);
    }
    result.face_start.push_back(int32_t(result.face_vertices.size()));
  }
  return result;
}

// Per vertex of `united`: the input vertex it lies at, if any.
std::vector<UnionVertex> vertex_origins(const PolygonMesh& united, const PolygonMesh& first, const PolygonMesh& second) {
  const auto less = [](Vec3 a, Vec3 b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  std::array<std::vector<Vec3>, 2> before{first.positions, second.positions};
  for (std::vector<Vec3>& points : before) std::sort(points.begin(), points.end(), less);
  std::vector<UnionVertex> origin(united.positions.size());
  for (size_t v = 0; v < origin.size(); ++v) {
    const Vec3 p = united.positions[v];
    origin[v] = std::binary_search(before[0].begin(), before[0].end(), p, less)   ? UnionVertex::first
                : std::binary_search(before[1].begin(), before[1].end(), p, less) ? UnionVertex::second
                                                                                  : UnionVertex::crossing;
  }
  return origin;
}

// The faces of `surface` within two rings of a vertex made where the surfaces cross.
std::vector<SurfaceMesh::Face_index> faces_near(const SurfaceMesh& surface, const std::vector<UnionVertex>& origin) {
  std::vector<uint8_t> ring(surface.num_vertices() + surface.number_of_removed_vertices(), 0);
  for (SurfaceMesh::Vertex_index v : surface.vertices()) ring[v.idx()] = origin[v.idx()] == UnionVertex::crossing;
  for (const uint8_t step : {uint8_t(1), uint8_t(2)}) // grow the flagged vertices by one ring, twice
    for (SurfaceMesh::Vertex_index v : surface.vertices())
      if (ring[v.idx()] == step)
        for (SurfaceMesh::Vertex_index w : surface.vertices_around_target(surface.halfedge(v)))
          if (!ring[w.idx()]) ring[w.idx()] = step + 1;
  std::vector<SurfaceMesh::Face_index> near;
  for (SurfaceMesh::Face_index f : surface.faces())
    for (SurfaceMesh::Vertex_index v : surface.vertices_around_face(surface.halfedge(f)))
      if (ring[v.idx()] == 1 || ring[v.idx()] == 2) {
        near.push_back(f);
        break;
      }
  return near;
}

// Rounded to floats, the thin triangles along the crossing of two surfaces that meet at
// a small angle may turn over and cross their neighbours (a few in a thousand bridges; the
// corefinement in double crosses nothing): the shortest edge of each face found
// crossing another there is collapsed into its end that came from the inputs (its
// position is kept exactly), a few rounds while any are found.
void uncross_rounded(SurfaceMesh& surface, const std::vector<UnionVertex>& origin) {
  for (int round = 0; round < 8; ++round) {
    std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> crossing;
    PMP::self_intersections(faces_near(surface, origin), surface, std::back_inserter(crossing));
    if (crossing.empty()) return;
    for (const auto& pair : crossing) {
      if (surface.is_removed(pair.first) || surface.is_removed(pair.second)) continue;
      SurfaceMesh::Halfedge_index shortest;
      double length = INFINITY;
      for (const SurfaceMesh::Face_index f : {pair.first, pair.second})
        for (SurfaceMesh::Halfedge_index h : surface.halfedges_around_face(surface.halfedge(f)))
          if (const double l = CGAL::squared_distance(surface.point(surface.source(h)), surface.point(surface.target(h)));
              l < length && CGAL::Euler::does_satisfy_link_condition(surface.edge(h), surface))
            length = l, shortest = h;
      if (shortest == SurfaceMesh::null_halfedge()) continue;
      const SurfaceMesh::Vertex_index from = surface.source(shortest), to = surface.target(shortest);
      const bool made_to = origin[to.idx()] == UnionVertex::crossing, made_from = origin[from.idx()] == UnionVertex::crossing;
      const Kernel::Point_3 kept = made_to && !made_from ? surface.point(from) : surface.point(to);
      surface.point(CGAL::Euler::collapse_edge(surface.edge(shortest), surface)) = kept;
    }
  }
}

} // namespace

SolidUnion unite_solids(const PolygonMesh& first, const PolygonMesh& second, std::string_view first_name,
                        std::string_view second_name) {
  SurfaceMesh a = solid(first, first_name), b = solid(second, second_name), out;
  if (!PMP::corefine_and_compute_union(a, b, out))
    throw TopologyError("union: the solids' union is not a manifold surface (they touch along an edge or at a point)");
  // Points where the surfaces cross are made in double; rounded to the floats Meander
  // keeps, a sliver's corners may fall on a line. Such faces go (collapsed or flipped
  // away by CGAL), so that no face is flat, and faces that then cross others are
  // collapsed, so that none cuts another.
  const PolygonMesh united = in_order_of_positions(to_polygons(out));
  SurfaceMesh rounded = to_surface(united, "union");
  PMP::remove_degenerate_faces(rounded);
  uncross_rounded(rounded, vertex_origins(united, first, second));
  rounded.collect_garbage();
  SolidUnion result{.mesh = to_polygons(rounded)};
  result.origin = vertex_origins(result.mesh, first, second);
  return result;
}

std::vector<uint8_t> inside_solid(const PolygonMesh& mesh, std::span<const Vec3> points, std::string_view name) {
  const SurfaceMesh surface = to_surface(mesh, name);
  if (!CGAL::is_closed(surface)) throw InputError("inside: the " + std::string(name) + " is not closed");
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel> side(surface);
  std::vector<uint8_t> inside(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    inside[i] = side({points[i].x, points[i].y, points[i].z}) == CGAL::ON_BOUNDED_SIDE;
  return inside;
}

} // namespace meander
