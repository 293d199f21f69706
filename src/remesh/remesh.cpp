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

// A triangle of a polygon cut into triangles: its corners (indices into the polygon,
// counter-clockwise) and the triangle across each side v[i] v[i+1] (-1: the polygon's own).
struct Triangle {
  std::array<int32_t, 3> v;
  std::array<int32_t, 3> across;
};

// Lawson's flips: each diagonal whose quad's fourth corner lies inside the circle of a
// triangle (by more than `tolerance`, in the units of the in-circle determinant) is
// flipped until none is, which leaves the polygon's constrained Delaunay triangulation
// (corners on one circle: the triangulation as it came, whatever the addresses).
void make_delaunay(std::vector<Triangle>& tris, const std::vector<double>& u, const std::vector<double>& w,
                   double tolerance, std::vector<int32_t>& stack) {
  stack.clear(); // sides, as 3 * triangle + side
  for (size_t t = 0; t < tris.size(); ++t)
    for (int32_t i = 0; i < 3; ++i)
      if (tris[t].across[size_t(i)] > int32_t(t)) stack.push_back(int32_t(3 * t) + i);
  const auto in_circle = [&](int32_t a, int32_t b, int32_t c, int32_t d) {
    const double ax = u[size_t(a)] - u[size_t(d)], ay = w[size_t(a)] - w[size_t(d)];
    const double bx = u[size_t(b)] - u[size_t(d)], by = w[size_t(b)] - w[size_t(d)];
    const double cx = u[size_t(c)] - u[size_t(d)], cy = w[size_t(c)] - w[size_t(d)];
    return (ax * ax + ay * ay) * (bx * cy - cx * by) - (bx * bx + by * by) * (ax * cy - cx * ay) +
           (cx * cx + cy * cy) * (ax * by - bx * ay);
  };
  const auto orient = [&](int32_t a, int32_t b, int32_t c) {
    return (u[size_t(b)] - u[size_t(a)]) * (w[size_t(c)] - w[size_t(a)]) -
           (w[size_t(b)] - w[size_t(a)]) * (u[size_t(c)] - u[size_t(a)]);
  };
  const auto side_of = [&](int32_t t, int32_t from) { // the side of t that starts at corner `from`
    for (int32_t i = 0; i < 3; ++i)
      if (tris[size_t(t)].v[size_t(i)] == from) return i;
    return -1;
  };
  while (!stack.empty()) {
    const int32_t t = stack.back() / 3, i = stack.back() % 3;
    stack.pop_back();
    const int32_t o = tris[size_t(t)].across[size_t(i)];
    if (o < 0) continue;
    const int32_t a = tris[size_t(t)].v[size_t(i)], b = tris[size_t(t)].v[size_t((i + 1) % 3)],
                  c = tris[size_t(t)].v[size_t((i + 2) % 3)];
    const int32_t j = side_of(o, b);
    if (j < 0 || tris[size_t(o)].v[size_t((j + 1) % 3)] != a) continue; // a side since flipped away
    const int32_t d = tris[size_t(o)].v[size_t((j + 2) % 3)];
    if (!(in_circle(a, b, c, d) > tolerance) || !(orient(a, d, c) > 0) || !(orient(d, b, c) > 0)) continue;
    // (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c).
    const int32_t ad = tris[size_t(o)].across[size_t((j + 1) % 3)], db = tris[size_t(o)].across[size_t((j + 2) % 3)];
    const int32_t bc = tris[size_t(t)].across[size_t((i + 1) % 3)], ca = tris[size_t(t)].across[size_t((i + 2) % 3)];
    tris[size_t(t)] = {{a, d, c}, {ad, o, ca}};
    tris[size_t(o)] = {{d, b, c}, {db, bc, t}};
    if (ad >= 0) tris[size_t(ad)].across[size_t(side_of(ad, d))] = t;
    if (bc >= 0) tris[size_t(bc)].across[size_t(side_of(bc, c))] = o;
    for (int32_t side : {3 * t, 3 * t + 2, 3 * o, 3 * o + 1}) stack.push_back(side);
  }
}

// Polygons of more than four corners cut into triangles here rather than by CGAL's
// triangulate_faces, whose constrained Delaunay triangulation flips edges in the order of
// its faces' addresses: a polygon with four points on a circle (a seam's split edge, a
// regular polygon) was cut one way or the other as the allocator placed them, so a
// Möbius band's curve changed with an unrelated command-line option. Ears go best first
// (the most equilateral of those that are convex and hold no other corner) in the plane
// of the polygon's Newell normal, then Lawson's flips make the cut Delaunay, as CGAL's
// was; quads keep CGAL's fixed rule. O(k^2) for k corners.
PolygonMesh triangulate_polygons(PolygonMesh mesh) {
  bool polygons = false;
  for (int32_t f = 0; f < mesh.num_faces() && !polygons; ++f) polygons = mesh.face(f).size() > 4;
  if (!polygons) return mesh;
  PolygonMesh out;
  out.positions = std::move(mesh.positions);
  out.face_vertices.reserve(mesh.face_vertices.size() * 3);
  std::vector<int32_t> prev, next, across, stack;
  std::vector<double> u, w, score;
  std::vector<Triangle> tris;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> face = mesh.face(f);
    const size_t k = face.size();
    if (k <= 4) {
      out.face_vertices.insert(out.face_vertices.end(), face.begin(), face.end());
      out.face_start.push_back(int32_t(out.face_vertices.size()));
      continue;
    }
    Vec3d normal{};
    for (size_t i = 0; i < k; ++i) {
      const Vec3d a = to_double(out.positions[size_t(face[i])]), b = to_double(out.positions[size_t(face[(i + 1) % k])]);
      normal = normal + Vec3d{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
    if (!(norm(normal) > 0))
      throw TopologyError("remeshing: polygon " + std::to_string(f) + " has no area, so it cannot be triangulated");
    const Vec3d axis = std::abs(normal.x) < std::abs(normal.y) && std::abs(normal.x) < std::abs(normal.z) ? Vec3d{1, 0, 0}
                       : std::abs(normal.y) < std::abs(normal.z)                                        ? Vec3d{0, 1, 0}
                                                                                                        : Vec3d{0, 0, 1};
    const Vec3d e1 = cross(normal, axis), e2 = cross(normal, e1);
    u.resize(k), w.resize(k), prev.resize(k), next.resize(k), score.resize(k), across.resize(k);
    for (size_t i = 0; i < k; ++i) {
      const Vec3d p = to_double(out.positions[size_t(face[i])]);
      u[i] = dot(p, e1), w[i] = dot(p, e2);
      prev[i] = int32_t((i + k - 1) % k), next[i] = int32_t((i + 1) % k);
    }
    // Twice the signed area of (a, b, c) in the plane, positive if counter-clockwise
    // seen along the normal (as the polygon runs), and what counts as none: corners split
    // along an edge in floats stray from it by rounding.
    const auto orient = [&](size_t a, size_t b, size_t c) {
      return (u[b] - u[a]) * (w[c] - w[a]) - (w[b] - w[a]) * (u[c] - u[a]);
    };
    const auto [u_low, u_high] = std::minmax_element(u.begin(), u.begin() + ptrdiff_t(k));
    const auto [w_low, w_high] = std::minmax_element(w.begin(), w.begin() + ptrdiff_t(k));
    const double flat = 1e-6 * std::max(*u_high - *u_low, *w_high - *w_low) * std::max(*u_high - *u_low, *w_high - *w_low);
    // An ear's merit: its shape (4 sqrt 3 area over the squared sides, 1 if equilateral),
    // lowered by 2 if another corner lies in it or on its new side and by 4 if it is not
    // convex, so that a polygon the plane makes self-overlapping is still cut.
    const auto merit = [&](size_t b) {
      const size_t a = size_t(prev[b]), c = size_t(next[b]);
      const double area2 = orient(a, b, c);
      const auto sq = [&](size_t i, size_t j) { return (u[i] - u[j]) * (u[i] - u[j]) + (w[i] - w[j]) * (w[i] - w[j]); };
      const double shape = 2 * std::sqrt(3.0) * area2 / std::max(sq(a, b) + sq(b, c) + sq(c, a), flat);
      if (!(area2 > flat)) return shape - 4;
      for (size_t p = size_t(next[c]); p != a; p = size_t(next[p]))
        if (orient(a, b, p) > -flat && orient(b, c, p) > -flat && orient(c, a, p) > -flat) return shape - 2;
      return shape;
    };
    for (size_t i = 0; i < k; ++i) score[i] = merit(i);
    // across[v]: the triangle beyond the side from v to next[v] (-1: the polygon's own);
    // each ear's new side, from c back to a, is its side 2.
    std::fill(across.begin(), across.begin() + ptrdiff_t(k), -1);
    const auto add = [&](size_t a, size_t b, size_t c) {
      const int32_t t = int32_t(tris.size());
      tris.push_back({{int32_t(a), int32_t(b), int32_t(c)}, {across[a], across[b], -1}});
      for (size_t v : {a, b})
        if (across[v] >= 0) tris[size_t(across[v])].across[2] = t;
      return t;
    };
    size_t start = 0;
    tris.clear();
    for (size_t left = k; left > 3; --left) {
      size_t best = start;
      for (size_t i = size_t(next[start]); i != start; i = size_t(next[i]))
        if (score[i] > score[best]) best = i;
      const size_t a = size_t(prev[best]), c = size_t(next[best]);
      across[a] = add(a, best, c);
      next[a] = int32_t(c), prev[c] = int32_t(a);
      start = a;
      score[a] = merit(a), score[c] = merit(c);
    }
    const size_t a = size_t(prev[start]), c = size_t(next[start]);
    const int32_t last = add(a, start, c);
    tris[size_t(last)].across[2] = across[c];
    if (across[c] >= 0) tris[size_t(across[c])].across[2] = last;
    make_delaunay(tris, u, w, flat * flat, stack);
    for (const Triangle& t : tris) {
      for (int32_t i : t.v) out.face_vertices.push_back(face[size_t(i)]);
      out.face_start.push_back(int32_t(out.face_vertices.size()));
    }
  }
  return out;
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
  CutMesh cut = cut_open(fine ? coarsen(mesh, kCoarse * length) : mesh, length * 4 / 3);
  cut.mesh = triangulate_polygons(std::move(cut.mesh));
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
