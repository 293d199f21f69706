#include "meander/check.h"

#include "meander/connectivity.h"
#include "mesh_scan.h"
#include "union_find.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>

namespace meander {

namespace {

// Relative to the squared bounding-box diagonal. Float coordinates resolve about 1e-7 of
// the model's size, so a face whose area is below (1e-6 diagonal)^2 has no shape that
// the file can express; exactly collinear vertices give ~1e-16 after rounding.
constexpr double kZeroAreaRelative = 1e-12;

// Twice the vector area of a face, in double.
double doubled_area(const PolygonMesh& m, std::span<const int32_t> face) {
  const Vec3 p0 = m.positions[size_t(face[0])];
  double x = 0, y = 0, z = 0;
  for (size_t i = 1; i + 1 < face.size(); ++i) {
    const Vec3 a = m.positions[size_t(face[i])], b = m.positions[size_t(face[i + 1])];
    const double ax = double(a.x) - p0.x, ay = double(a.y) - p0.y, az = double(a.z) - p0.z;
    const double bx = double(b.x) - p0.x, by = double(b.y) - p0.y, bz = double(b.z) - p0.z;
    x += ay * bz - az * by;
    y += az * bx - ax * bz;
    z += ax * by - ay * bx;
  }
  return std::sqrt(x * x + y * y + z * z);
}

// Makes each boundary loop one set of `corners` (EdgeScan::fans): a boundary edge
// joins the fans at its two ends, and a fan the two boundary edges that end it. Where a
// fan ends at a non-manifold edge instead, the boundary has no single way on: the fans
// at that vertex left with one boundary end are joined, as one walk along the boundary
// would pass from one to the next.
void join_boundary_loops(const PolygonMesh& m, const Connectivity& c, UnionFind& corners, bool non_manifold_edges) {
  if (non_manifold_edges) {
    std::vector<uint8_t> ends(size_t(m.num_corners()), 0); // boundary edges ending each fan (2 is plenty)
    const auto for_each_boundary_corner = [&](auto&& visit) {
      for (int32_t e = 0; e < c.num_edges(); ++e)
        if (c.edge_degree(e) == 1) {
          const int32_t h = c.halfedges(e)[0];
          visit(h);
          visit(next_halfedge(m, c, h));
        }
    };
    for_each_boundary_corner([&](int32_t h) {
      uint8_t& n = ends[size_t(corners.find(h))];
      n = uint8_t(std::min(n + 1, 2));
    });
    std::vector<int32_t> open_fan(size_t(m.num_vertices()), -1); // a fan at the vertex with one boundary end
    for_each_boundary_corner([&](int32_t h) {
      if (ends[size_t(corners.find(h))] != 1) return;
      int32_t& first = open_fan[size_t(m.face_vertices[size_t(h)])];
      if (first < 0) first = h;
      else corners.unite(first, h);
    });
  }
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) == 1) {
      const int32_t h = c.halfedges(e)[0];
      corners.unite(h, next_halfedge(m, c, h));
    }
}

// The topology part of inspect() on faces that are all polygons with indices in range.
void inspect_topology(const PolygonMesh& m, MeshReport& report) {
  const Connectivity c = build_connectivity(m);
  EdgeScan edges = scan_edges(m, c);
  report.edges = c.num_edges();
  report.boundary_edges = edges.boundary;
  report.non_manifold_edges = edges.non_manifold;
  report.misoriented_edges = edges.misoriented;
  report.duplicate_faces = int32_t(edges.duplicates.size());

  // Components: sheets joined across non-manifold edges, numbered by their first face
  // (sheets are numbered that way already).
  const Sheets sheets = find_sheets(m, c);
  const auto sheet_of_halfedge = [&](int32_t h) { return sheets.sheet[size_t(c.face_of(h))]; };
  UnionFind glued(sheets.size());
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) > 2)
      for (const int32_t h : c.halfedges(e)) glued.unite(sheet_of_halfedge(c.halfedges(e)[0]), sheet_of_halfedge(h));
  std::vector<int32_t> component_of_sheet(size_t(sheets.size())), number(size_t(sheets.size()), -1);
  for (int32_t s = 0; s < sheets.size(); ++s) {
    int32_t& n = number[size_t(glued.find(s))];
    if (n < 0) {
      n = int32_t(report.components.size());
      report.components.emplace_back();
    }
    component_of_sheet[size_t(s)] = n;
  }
  std::vector<ComponentReport>& components = report.components;
  const auto component = [&](int32_t f) -> ComponentReport& {
    return components[size_t(component_of_sheet[size_t(sheets.sheet[size_t(f)])])];
  };
  for (int32_t s = 0; s < sheets.size(); ++s)
    if (!sheets.orientable[size_t(s)]) components[size_t(component_of_sheet[size_t(s)])].orientable = false;
  report.face_components.resize(size_t(m.num_faces()));
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const int32_t k = component_of_sheet[size_t(sheets.sheet[size_t(f)])];
    report.face_components[size_t(f)] = k;
    ++components[size_t(k)].faces;
  }
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    ComponentReport& k = component(c.face_of(c.halfedges(e)[0]));
    ++k.edges;
    k.misoriented_edges += misoriented(m, c, e);
    if (c.edge_degree(e) > 2) k.manifold = false;
  }

  // A vertex counts once per component: a manifold vertex is one fan, so in one
  // component; the few fans of non-manifold vertices are sorted out apart.
  UnionFind& corners = edges.fans;
  const std::vector<int32_t> fans = count_fans(m, corners);
  std::vector<std::pair<int32_t, int32_t>> shared; // (vertex, component) of each fan of a non-manifold vertex
  for (int32_t h = 0; h < m.num_corners(); ++h) {
    if (!corners.is_root(h)) continue;
    const int32_t v = m.face_vertices[size_t(h)];
    ComponentReport& k = component(c.face_of(h));
    if (fans[size_t(v)] == 1) {
      ++k.vertices;
    } else {
      k.manifold = false;
      shared.emplace_back(v, int32_t(&k - components.data()));
    }
  }
  std::sort(shared.begin(), shared.end());
  shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
  for (const auto& [v, k] : shared) ++components[size_t(k)].vertices;
  for (const int32_t n : fans) report.non_manifold_vertices += n > 1;

  join_boundary_loops(m, c, corners, report.non_manifold_edges > 0);
  std::vector<bool> counted(size_t(m.num_corners()), false);
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) == 1) {
      const int32_t h = c.halfedges(e)[0];
      const int32_t loop = corners.find(h);
      if (counted[size_t(loop)]) continue;
      counted[size_t(loop)] = true;
      ++report.boundary_loops;
      ++component(c.face_of(h)).boundary_loops;
    }

  for (ComponentReport& k : components) {
    k.euler_characteristic = int64_t(k.vertices) - k.edges + k.faces;
    const int64_t deficit = 2 - k.euler_characteristic - k.boundary_loops;
    if (k.manifold) k.genus = int32_t(k.orientable ? deficit / 2 : deficit);
    report.orientable = report.orientable && k.orientable;
  }
}

} // namespace

MeshReport inspect(const PolygonMesh& mesh) {
  const int32_t nv = mesh.num_vertices(), nf = mesh.num_faces();
  MeshReport report;
  report.vertices = nv;
  report.faces = nf;

  std::vector<uint8_t> used(size_t(nv), 0);
  std::vector<int32_t> by_size;
  RepeatFinder repeats(nv);
  bool all_polygons = true; // every face goes into the topology as it is
  for (int32_t f = 0; f < nf; ++f) {
    const std::span<const int32_t> face = mesh.face(f);
    if (face.size() >= by_size.size()) by_size.resize(face.size() + 1, 0);
    ++by_size[face.size()];
    const auto bad = std::count_if(face.begin(), face.end(), [&](int32_t v) { return !in_range(v, nv); });
    if (bad > 0) {
      report.out_of_range_indices += int32_t(bad);
      all_polygons = false;
      continue;
    }
    for (const int32_t v : face) used[size_t(v)] = 1;
    if (face.size() < 3 || repeats(face) >= 0) {
      ++report.degenerate_faces;
      all_polygons = false;
    }
  }
  for (size_t n = 0; n < by_size.size(); ++n)
    if (by_size[n] > 0) report.faces_by_size[int32_t(n)] = by_size[n];
  for (int32_t v = 0; v < nv; ++v) {
    const Vec3 p = mesh.positions[size_t(v)];
    const bool finite = is_finite(p);
    report.non_finite_positions += !finite;
    report.unreferenced_vertices += !used[size_t(v)];
    if (used[size_t(v)] && finite) report.bounding_box.extend(p);
  }

  const double diagonal = report.bounding_box.diagonal();
  const double zero_area = 2 * kZeroAreaRelative * diagonal * diagonal;
  for (int32_t f = 0; f < nf; ++f) {
    const std::span<const int32_t> face = mesh.face(f);
    if (face.size() < 3 || !all_in_range(face, nv) || repeats(face) >= 0) continue;
    if (!std::all_of(face.begin(), face.end(), [&](int32_t v) { return is_finite(mesh.positions[size_t(v)]); })) continue;
    report.zero_area_faces += doubled_area(mesh, face) < zero_area;
  }

  if (all_polygons) {
    inspect_topology(mesh, report);
  } else {
    PolygonMesh polygons = mesh;
    std::vector<int32_t> origin;
    clean_faces(polygons, origin);
    inspect_topology(polygons, report);
    // Back to the input's face numbers.
    std::vector<int32_t> face_components(size_t(nf), -1);
    for (size_t f = 0; f < origin.size(); ++f) face_components[size_t(origin[f])] = report.face_components[f];
    report.face_components = std::move(face_components);
  }
  return report;
}

} // namespace meander
