#include "meander/check.h"

#include "meander/error.h"
#include "meander/io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

namespace meander {
namespace {

// ---------------------------------------------------------------- shapes and helpers

PolygonMesh tetrahedron() {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto f : {std::array{0, 2, 1}, std::array{0, 1, 3}, std::array{0, 3, 2}, std::array{1, 2, 3}}) m.add_face(f);
  return m;
}

// Unit cube of six outward quads; vertex x + 2y + 4z sits at (x, y, z).
PolygonMesh cube() {
  PolygonMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  for (auto f : {std::array{0, 2, 3, 1}, std::array{4, 5, 7, 6}, std::array{0, 1, 5, 4}, std::array{2, 6, 7, 3},
                 std::array{0, 4, 6, 2}, std::array{1, 3, 7, 5}})
    m.add_face(f);
  return m;
}

// A strip of 2n triangles over the bottom vertices 0..n and the top vertices n+1..2n+1.
PolygonMesh strip(int n) {
  PolygonMesh m;
  for (int i = 0; i <= n; ++i) m.positions.push_back({float(i), 0, 0});
  for (int i = 0; i <= n; ++i) m.positions.push_back({float(i), 1, 0});
  for (int i = 0; i < n; ++i) {
    const int b = i, t = n + 1 + i;
    m.add_face({b, b + 1, t + 1});
    m.add_face({b, t + 1, t});
  }
  return m;
}

// A band of n quads around the z axis with a half twist: top and bottom swap at the seam.
PolygonMesh moebius_band(int n) {
  PolygonMesh m;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n, t = a / 2;
    const double cx = std::cos(a), cy = std::sin(a);
    const double dx = 0.3 * std::cos(t) * cx, dy = 0.3 * std::cos(t) * cy, dz = 0.3 * std::sin(t);
    m.positions.push_back({float(cx + dx), float(cy + dy), float(dz)});  // top i = 2i
    m.positions.push_back({float(cx - dx), float(cy - dy), float(-dz)}); // bottom i = 2i+1
  }
  for (int i = 0; i + 1 < n; ++i) m.add_face({2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1});
  m.add_face({2 * (n - 1), 1, 0, 2 * (n - 1) + 1});
  return m;
}

// Two triangles touching at vertex 0 only.
PolygonMesh bow_tie() {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  m.add_face({0, 1, 2});
  m.add_face({0, 3, 4});
  return m;
}

// Three triangles on the edge (0,1), like the pages of a book.
PolygonMesh three_triangles_on_one_edge() {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.add_face({0, 1, 2});
  m.add_face({1, 0, 3});
  m.add_face({0, 1, 4});
  return m;
}

// Two closed tetrahedra whose only common element is vertex 0.
PolygonMesh two_tetrahedra_sharing_a_vertex() {
  PolygonMesh m = tetrahedron();
  m.positions.push_back({-1, 0, 0});
  m.positions.push_back({0, -1, 0});
  m.positions.push_back({0, 0, -1});
  for (auto f : {std::array{0, 5, 4}, std::array{0, 4, 6}, std::array{0, 6, 5}, std::array{4, 5, 6}}) m.add_face(f);
  return m;
}

PolygonMesh with_face_replaced(PolygonMesh m, int32_t f, std::initializer_list<int32_t> vertices) {
  PolygonMesh out;
  out.positions = m.positions;
  for (int32_t g = 0; g < m.num_faces(); ++g) {
    if (g == f)
      out.add_face(vertices);
    else
      out.add_face(m.face(g));
  }
  return out;
}

double face_area(const PolygonMesh& m, int32_t f) {
  const auto face = m.face(f);
  const Vec3 p0 = m.positions[size_t(face[0])];
  double n[3] = {0, 0, 0};
  for (size_t i = 1; i + 1 < face.size(); ++i) {
    const Vec3 a = m.positions[size_t(face[i])] - p0, b = m.positions[size_t(face[i + 1])] - p0;
    n[0] += double(a.y) * b.z - double(a.z) * b.y;
    n[1] += double(a.z) * b.x - double(a.x) * b.z;
    n[2] += double(a.x) * b.y - double(a.y) * b.x;
  }
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

double total_area(const PolygonMesh& m) {
  double area = 0;
  for (int32_t f = 0; f < m.num_faces(); ++f) area += face_area(m, f);
  return area;
}

// The area of the faces with distinct vertex sets, found independently of inspect.cpp.
double area_without_duplicates(const PolygonMesh& m) {
  std::set<std::vector<int32_t>> seen;
  double area = 0;
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    std::vector<int32_t> key(m.face(f).begin(), m.face(f).end());
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second) area += face_area(m, f);
  }
  return area;
}

// What repair promises of its result, checked by inspect.
void expect_repaired(const PolygonMesh& m) {
  const MeshReport r = inspect(m);
  EXPECT_GT(r.faces, 0);
  EXPECT_EQ(r.non_manifold_edges, 0);
  EXPECT_EQ(r.non_manifold_vertices, 0);
  EXPECT_EQ(r.degenerate_faces, 0);
  EXPECT_EQ(r.duplicate_faces, 0);
  EXPECT_EQ(r.unreferenced_vertices, 0);
  EXPECT_EQ(r.out_of_range_indices, 0);
  EXPECT_EQ(r.non_finite_positions, 0);
  for (size_t k = 0; k < r.components.size(); ++k) {
    EXPECT_TRUE(r.components[k].manifold) << "component " << k;
    if (r.components[k].orientable) {
      EXPECT_EQ(r.components[k].misoriented_edges, 0) << "component " << k;
    }
  }
}

// The number N in the repair line that starts with `start` ("re-oriented N faces ..."), 0 if none.
int repair_count(const RepairResult& r, const std::string& start) {
  for (const std::string& line : r.repairs)
    if (line.rfind(start, 0) == 0) return std::stoi(line.substr(start.size()));
  return 0;
}

// The message of repair's refusal in strict mode, or "(no error)".
std::string strict_error(const PolygonMesh& m, std::string_view name = "x.obj") {
  try {
    repair(m, name, {.strict = true});
  } catch (const TopologyError& e) {
    return e.what();
  }
  return "(no error)";
}

// ---------------------------------------------------------------- inspect, shapes in code

// The smallest closed surface: every count is known by hand.
TEST(CheckInspect, Tetrahedron) {
  const MeshReport r = inspect(tetrahedron());
  EXPECT_EQ(r.vertices, 4);
  EXPECT_EQ(r.faces, 4);
  EXPECT_EQ(r.faces_by_size, (std::map<int32_t, int32_t>{{3, 4}}));
  EXPECT_EQ(r.edges, 6);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_EQ(r.boundary_loops, 0);
  EXPECT_EQ(r.misoriented_edges, 0);
  EXPECT_TRUE(r.orientable);
  EXPECT_EQ(r.bounding_box.min, (Vec3{0, 0, 0}));
  EXPECT_EQ(r.bounding_box.max, (Vec3{1, 1, 1}));
  ASSERT_EQ(r.components.size(), 1u);
  const ComponentReport& k = r.components[0];
  EXPECT_EQ(k.faces, 4);
  EXPECT_EQ(k.vertices, 4);
  EXPECT_EQ(k.edges, 6);
  EXPECT_EQ(k.euler_characteristic, 2);
  EXPECT_TRUE(k.manifold);
  EXPECT_EQ(k.genus, 0);
}

// Quads: edges are counted per polygon side, not per triangle of a triangulation.
TEST(CheckInspect, CubeOfQuads) {
  const MeshReport r = inspect(cube());
  EXPECT_EQ(r.faces_by_size, (std::map<int32_t, int32_t>{{4, 6}}));
  EXPECT_EQ(r.edges, 12);
  EXPECT_EQ(r.misoriented_edges, 0);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].euler_characteristic, 2);
  EXPECT_EQ(r.components[0].genus, 0);
}

// An annulus: genus from chi = 2 - 2g - b needs both boundary loops counted.
TEST(CheckInspect, AnnulusHasTwoBoundaryLoops) {
  PolygonMesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  for (int i = 0; i < 4; ++i) m.add_face({i, 4 + i, 4 + (i + 1) % 4, (i + 1) % 4});
  const MeshReport r = inspect(m);
  EXPECT_EQ(r.boundary_edges, 8);
  EXPECT_EQ(r.boundary_loops, 2);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].euler_characteristic, 0);
  EXPECT_EQ(r.components[0].genus, 0);
}

// Two triangles touching at one vertex: its two boundary loops meet there, and pairing
// boundary edges by vertex alone would merge them into one. Edge-connected, the bow-tie
// is two components (as repair leaves it).
TEST(CheckInspect, BowTie) {
  const MeshReport r = inspect(bow_tie());
  EXPECT_EQ(r.non_manifold_vertices, 1);
  EXPECT_EQ(r.non_manifold_edges, 0);
  EXPECT_EQ(r.boundary_edges, 6);
  EXPECT_EQ(r.boundary_loops, 2);
  ASSERT_EQ(r.components.size(), 2u);
  for (const ComponentReport& k : r.components) {
    EXPECT_EQ(k.vertices, 3);
    EXPECT_EQ(k.boundary_loops, 1);
    EXPECT_FALSE(k.manifold);
    EXPECT_EQ(k.genus, -1);
  }
}

// Three faces on one edge: the edge is kept once (not dropped, not counted twice), and
// both of its ends are non-manifold vertices, each with three fans. The boundary has no
// single way on at those ends: walking it passes from page to page, one loop.
TEST(CheckInspect, ThreeTrianglesOnOneEdge) {
  const MeshReport r = inspect(three_triangles_on_one_edge());
  EXPECT_EQ(r.edges, 7);
  EXPECT_EQ(r.non_manifold_edges, 1);
  EXPECT_EQ(r.non_manifold_vertices, 2);
  EXPECT_EQ(r.boundary_edges, 6);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.misoriented_edges, 0); // only manifold edges can be misoriented
  ASSERT_EQ(r.components.size(), 1u); // joined across the non-manifold edge
  EXPECT_FALSE(r.components[0].manifold);
  EXPECT_EQ(r.components[0].genus, -1);
}

// Two closed fans at one vertex: every edge there has two faces and every count per
// vertex looks manifold; only following the fans shows the vertex is pinched.
TEST(CheckInspect, TwoTetrahedraSharingAVertex) {
  const MeshReport r = inspect(two_tetrahedra_sharing_a_vertex());
  EXPECT_EQ(r.non_manifold_vertices, 1);
  EXPECT_EQ(r.non_manifold_edges, 0);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_EQ(r.vertices - r.unreferenced_vertices - r.edges + r.faces, 3);
  ASSERT_EQ(r.components.size(), 2u);
  for (const ComponentReport& k : r.components) {
    EXPECT_EQ(k.vertices, 4); // the shared vertex counts in both
    EXPECT_EQ(k.euler_characteristic, 2);
    EXPECT_FALSE(k.manifold);
  }
}

// One face wound the other way: both of its interior edges are crossed the same way by
// their two faces, yet the strip is orientable.
TEST(CheckInspect, StripWithOneFaceFlipped) {
  const PolygonMesh m = with_face_replaced(strip(3), 2, {6, 2, 1});
  const MeshReport r = inspect(m);
  EXPECT_EQ(r.misoriented_edges, 2);
  EXPECT_TRUE(r.orientable);
  EXPECT_EQ(r.boundary_loops, 1);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].genus, 0);
}

// A Möbius band crosses the seam edge the same way from both sides whatever the faces'
// orientation: non-orientable, one boundary loop, one cross-cap.
TEST(CheckInspect, MoebiusStripOfQuads) {
  const MeshReport r = inspect(moebius_band(6));
  EXPECT_FALSE(r.orientable);
  EXPECT_EQ(r.edges, 18);
  EXPECT_EQ(r.boundary_edges, 12);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_GE(r.misoriented_edges, 1);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_FALSE(r.components[0].orientable);
  EXPECT_EQ(r.components[0].euler_characteristic, 0);
  EXPECT_EQ(r.components[0].genus, 1); // cross-caps
}

// A copy of a face wound the other way round is still the same face; it also makes each
// of its edges non-manifold.
TEST(CheckInspect, DuplicateFaceWithOppositeOrientation) {
  PolygonMesh m = tetrahedron();
  m.add_face({2, 0, 1}); // face 0 is (0, 2, 1): reversed and rotated
  const MeshReport r = inspect(m);
  EXPECT_EQ(r.duplicate_faces, 1);
  EXPECT_EQ(r.non_manifold_edges, 3);
  EXPECT_EQ(r.degenerate_faces, 0);
}

// A repeated consecutive index is a face with a zero-length side: degenerate as given,
// but its topology is that of the collapsed triangle.
TEST(CheckInspect, FaceWithRepeatedConsecutiveIndex) {
  const MeshReport r = inspect(with_face_replaced(tetrahedron(), 3, {1, 2, 2, 3}));
  EXPECT_EQ(r.degenerate_faces, 1);
  EXPECT_EQ(r.faces_by_size, (std::map<int32_t, int32_t>{{3, 3}, {4, 1}}));
  EXPECT_EQ(r.edges, 6);
  EXPECT_EQ(r.boundary_edges, 0);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].genus, 0);
}

// Each input face names its component, in the input's face numbers even where faces
// were left out of the topology (check_printability sums volumes with them).
TEST(CheckInspect, FaceComponentsFollowTheInputFaces) {
  PolygonMesh m = two_tetrahedra_sharing_a_vertex();
  m.add_face({0, 0, 1}); // fewer than 3 vertices once collapsed: left out
  const int32_t collapsed = m.num_faces();
  m.add_face({1, 2, 2, 3}); // collapsed to a triangle of the first tetrahedron: kept
  const MeshReport r = inspect(m);
  ASSERT_EQ(r.face_components.size(), size_t(m.num_faces()));
  ASSERT_EQ(r.components.size(), 2u);
  for (int32_t f = 0; f < 4; ++f) EXPECT_EQ(r.face_components[size_t(f)], 0);
  for (int32_t f = 4; f < 8; ++f) EXPECT_EQ(r.face_components[size_t(f)], 1);
  EXPECT_EQ(r.face_components[size_t(collapsed - 1)], -1);
  EXPECT_EQ(r.face_components[size_t(collapsed)], 0);
}

// Vertices no face uses take no part in the topology or the bounding box.
TEST(CheckInspect, UnreferencedVertices) {
  PolygonMesh m = tetrahedron();
  m.positions.push_back({100, 100, 100});
  const MeshReport r = inspect(m);
  EXPECT_EQ(r.unreferenced_vertices, 1);
  EXPECT_EQ(r.bounding_box.max, (Vec3{1, 1, 1}));
  EXPECT_EQ(r.components[0].vertices, 4);
}

// NaN must neither poison the bounding box nor the area test.
TEST(CheckInspect, NanPosition) {
  PolygonMesh m = tetrahedron();
  m.positions[3].x = NAN;
  const MeshReport r = inspect(m);
  EXPECT_EQ(r.non_finite_positions, 1);
  EXPECT_EQ(r.zero_area_faces, 0);
  EXPECT_EQ(r.bounding_box.max, (Vec3{1, 1, 0}));
}

// Indices past either end must not be followed: such faces are counted and left out of
// the topology, which is then that of the other faces.
TEST(CheckInspect, OutOfRangeIndex) {
  PolygonMesh m = with_face_replaced(tetrahedron(), 3, {1, 2, 9});
  m.add_face({-1, 0, 1});
  const MeshReport r = inspect(m);
  EXPECT_EQ(r.out_of_range_indices, 2);
  EXPECT_EQ(r.faces, 5);
  EXPECT_EQ(r.edges, 6);
  EXPECT_EQ(r.boundary_edges, 3);
  EXPECT_EQ(r.boundary_loops, 1);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].faces, 3);
}

// Collinear but distinct vertices: no repeated index, yet no area.
TEST(CheckInspect, ZeroAreaFace) {
  PolygonMesh m = strip(1);
  m.positions.push_back({0.5f, 0, 0});
  m.add_face({0, 4, 1}); // on the strip's bottom edge
  const MeshReport r = inspect(m);
  EXPECT_EQ(r.zero_area_faces, 1);
  EXPECT_EQ(r.degenerate_faces, 0);
}

TEST(CheckInspect, EmptyMesh) {
  const MeshReport r = inspect(PolygonMesh{});
  EXPECT_EQ(r.faces, 0);
  EXPECT_EQ(r.edges, 0);
  EXPECT_TRUE(r.components.empty());
  EXPECT_TRUE(r.bounding_box.empty());
}

// ---------------------------------------------------------------- repair, shapes in code

// Nothing to do: no line, the same arrays, and the rvalue overload hands over the memory.
TEST(CheckRepair, CleanMeshIsReturnedUnchanged) {
  for (const PolygonMesh& m : {tetrahedron(), cube(), strip(4)}) {
    const RepairResult r = repair(m, "x.obj", {.strict = true});
    EXPECT_TRUE(r.repairs.empty());
    EXPECT_EQ(r.mesh.positions, m.positions);
    EXPECT_EQ(r.mesh.face_start, m.face_start);
    EXPECT_EQ(r.mesh.face_vertices, m.face_vertices);
  }
  PolygonMesh m = tetrahedron();
  const int32_t* data = m.face_vertices.data();
  const RepairResult r = repair(std::move(m), "x.obj");
  EXPECT_EQ(r.mesh.face_vertices.data(), data);
}

// The connectivity repair hands on must be exactly the one the pipeline would build,
// also after dropping duplicate faces, splitting fans and renumbering vertices; after
// re-orienting faces it is left empty (their halfedges changed).
TEST(CheckRepair, HandsOnTheConnectivityOfItsResult) {
  auto expect_same = [](const RepairResult& r) {
    const Connectivity fresh = build_connectivity(r.mesh);
    EXPECT_EQ(r.connectivity.halfedge_edge, fresh.halfedge_edge);
    EXPECT_EQ(r.connectivity.halfedge_face, fresh.halfedge_face);
    EXPECT_EQ(r.connectivity.face_size, fresh.face_size);
    EXPECT_EQ(r.connectivity.edge_vertices, fresh.edge_vertices);
    EXPECT_EQ(r.connectivity.edge_start, fresh.edge_start);
    EXPECT_EQ(r.connectivity.edge_halfedges, fresh.edge_halfedges);
  };
  expect_same(repair(cube(), "x.obj"));
  PolygonMesh unused = strip(3);
  unused.positions.insert(unused.positions.begin(), Vec3{9, 9, 9}); // vertex 0 unused
  for (int32_t& v : unused.face_vertices) ++v;
  const RepairResult dropped = repair(unused, "x.obj");
  ASSERT_FALSE(dropped.repairs.empty());
  expect_same(dropped);
  PolygonMesh duplicated = tetrahedron();
  duplicated.add_face({1, 2, 3});
  expect_same(repair(duplicated, "x.obj"));
  expect_same(repair(bow_tie(), "x.obj"));
  PolygonMesh flipped = strip(3);
  std::reverse(flipped.face_vertices.begin(), flipped.face_vertices.begin() + 3);
  const RepairResult reoriented = repair(flipped, "x.obj");
  ASSERT_FALSE(reoriented.repairs.empty());
  EXPECT_TRUE(reoriented.connectivity.halfedge_edge.empty());
}

TEST(CheckRepair, BowTieVertexIsSplit) {
  const PolygonMesh m = bow_tie();
  EXPECT_EQ(strict_error(m), "x.obj: vertex 0 joins 2 separate fans of faces: mesh is not manifold");
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"split 1 non-manifold vertex into 2 copies (vertex 0 had 2 fans)"});
  // The first fan keeps the vertex, the copy is appended with the same position.
  ASSERT_EQ(r.mesh.num_vertices(), 6);
  EXPECT_EQ(r.mesh.positions[5], m.positions[0]);
  EXPECT_EQ(std::vector<int32_t>(r.mesh.face(1).begin(), r.mesh.face(1).end()), (std::vector<int32_t>{5, 3, 4}));
  expect_repaired(r.mesh);
  EXPECT_EQ(inspect(r.mesh).components.size(), 2u);
}

// A closed fan (a tetrahedron's corner) and an open one (three triangles) at vertex 0,
// in both orders: walked round from the vertex's first corner, either fan shows that it
// holds only some of the vertex's corners.
TEST(CheckRepair, ClosedAndOpenFanAtOneVertexAreSplit) {
  const PolygonMesh closed = tetrahedron();
  PolygonMesh open;
  open.positions = {{0, 0, 0}, {-1, 0, 0}, {-1, -1, 0}, {0, -1, -0.5f}, {0.5f, -1, -1}};
  open.add_face({0, 1, 2});
  open.add_face({0, 2, 3});
  open.add_face({0, 3, 4});
  for (const bool closed_first : {true, false}) {
    const PolygonMesh& a = closed_first ? closed : open;
    const PolygonMesh& b = closed_first ? open : closed;
    PolygonMesh m = a;
    for (int32_t v = 1; v < b.num_vertices(); ++v) m.positions.push_back(b.positions[size_t(v)]);
    for (int32_t f = 0; f < b.num_faces(); ++f) {
      std::vector<int32_t> face(b.face(f).begin(), b.face(f).end());
      for (int32_t& v : face) v = v == 0 ? 0 : v + a.num_vertices() - 1;
      m.add_face(face);
    }
    const RepairResult r = repair(m, "x.obj");
    EXPECT_EQ(r.repairs, std::vector<std::string>{"split 1 non-manifold vertex into 2 copies (vertex 0 had 2 fans)"})
        << closed_first;
    expect_repaired(r.mesh);
    EXPECT_EQ(inspect(r.mesh).components.size(), 2u);
  }
}

// Fans are joined on all threads at once. 20000 copies of the mesh above (a closed and an
// open fan at one vertex), faces interleaved so that every copy spans many threads' share
// of the edges, with duplicates of a few faces: every copy's vertex must be split once
// and every duplicate found, whatever the threads did.
TEST(CheckRepair, FansAndDuplicatesAreFoundAcrossThreads) {
  PolygonMesh one = tetrahedron();
  const int32_t apex = one.num_vertices();
  for (const Vec3 p : {Vec3{-1, 0, 0}, Vec3{-1, -1, 0}, Vec3{0, -1, -0.5f}, Vec3{0.5f, -1, -1}}) one.positions.push_back(p);
  for (int32_t k = 0; k < 3; ++k) one.add_face(std::array<int32_t, 3>{0, apex + k, apex + k + 1});
  constexpr int32_t copies = 20000;
  PolygonMesh m;
  for (int32_t c = 0; c < copies; ++c)
    for (const Vec3 p : one.positions) m.positions.push_back(p + Vec3{float(c % 200) * 3, float(c / 200) * 3, 0});
  for (int32_t f = 0; f < one.num_faces(); ++f)
    for (int32_t c = 0; c < copies; ++c) {
      std::vector<int32_t> face(one.face(f).begin(), one.face(f).end());
      for (int32_t& v : face) v += c * one.num_vertices();
      m.add_face(face);
    }
  for (int32_t c = 0; c < copies; c += 1000) m.add_face(m.face(c)); // a duplicate of copy c's first face
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, (std::vector<std::string>{
                           "dropped 20 duplicate faces (face 140000 duplicates face 0)",
                           "split 20000 non-manifold vertices into 40000 copies (vertex 0 had 2 fans)"}));
  expect_repaired(r.mesh);
  EXPECT_EQ(inspect(r.mesh).components.size(), 2u * copies);
}

TEST(CheckRepair, ThreeTrianglesOnOneEdgeAreCutApart) {
  const PolygonMesh m = three_triangles_on_one_edge();
  EXPECT_EQ(strict_error(m), "x.obj: edge (0,1) is shared by 3 faces: mesh is not manifold");
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, (std::vector<std::string>{"cut 1 non-manifold edge (edge (0,1) was shared by 3 faces)",
                                                 "split 2 non-manifold vertices into 6 copies (vertex 0 had 3 fans)"}));
  expect_repaired(r.mesh);
  const MeshReport after = inspect(r.mesh);
  EXPECT_EQ(after.vertices, 9);
  EXPECT_EQ(after.components.size(), 3u);
  EXPECT_EQ(after.boundary_loops, 3);
  EXPECT_DOUBLE_EQ(total_area(r.mesh), total_area(m));
}

TEST(CheckRepair, TwoTetrahedraSharingAVertexSeparate) {
  const RepairResult r = repair(two_tetrahedra_sharing_a_vertex(), "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"split 1 non-manifold vertex into 2 copies (vertex 0 had 2 fans)"});
  expect_repaired(r.mesh);
  const MeshReport after = inspect(r.mesh);
  ASSERT_EQ(after.components.size(), 2u);
  for (const ComponentReport& k : after.components) EXPECT_EQ(k.genus, 0);
}

TEST(CheckRepair, StripWithOneFaceFlippedIsReoriented) {
  const PolygonMesh m = with_face_replaced(strip(3), 2, {6, 2, 1});
  EXPECT_EQ(strict_error(m), "x.obj: faces 2 and 3 disagree in orientation across edge (1,6)");
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"re-oriented 1 face to agree with their neighbours (first: face 2)"});
  EXPECT_EQ(r.mesh.face_start, strip(3).face_start);
  expect_repaired(r.mesh);
  EXPECT_EQ(inspect(r.mesh).misoriented_edges, 0);
}

// Half the faces each way: the first face decides.
TEST(CheckRepair, OrientationTieKeepsTheFirstFace) {
  const PolygonMesh m = with_face_replaced(strip(1), 1, {0, 2, 3});
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"re-oriented 1 face to agree with their neighbours (first: face 1)"});
  EXPECT_EQ(r.mesh.face(0)[1], m.face(0)[1]);
}

// Non-orientability is no error, not even in strict mode: the cycle handles it.
TEST(CheckRepair, MoebiusStripIsLeftAsItIs) {
  const PolygonMesh m = moebius_band(6);
  const RepairResult strict = repair(m, "x.obj", {.strict = true});
  EXPECT_EQ(strict.mesh.face_vertices, m.face_vertices);
  const RepairResult r = repair(m, "x.obj");
  EXPECT_TRUE(r.repairs.empty());
  EXPECT_EQ(r.notices,
            std::vector<std::string>{"component 0 is not orientable (Möbius-like); faces left as they are"});
  EXPECT_EQ(r.mesh.face_vertices, m.face_vertices);
  expect_repaired(r.mesh);
}

TEST(CheckRepair, DuplicateFaceWithOppositeOrientationIsDropped) {
  PolygonMesh m = tetrahedron();
  m.add_face({2, 0, 1});
  EXPECT_EQ(strict_error(m), "x.obj: face 4 duplicates face 0");
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"dropped 1 duplicate face (face 4 duplicates face 0)"});
  EXPECT_EQ(r.mesh.face_vertices, tetrahedron().face_vertices);
  expect_repaired(r.mesh);
}

// Two copies of a triangle alone make a closed "pillow" whose edges are all manifold, so
// the copy is found across a manifold edge; three copies share only non-manifold edges,
// where the copies must still be told from the faces merely sharing an edge.
TEST(CheckRepair, CopiesOfATriangleAreFoundWithOrWithoutManifoldEdges) {
  PolygonMesh pillow;
  pillow.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  pillow.add_face({0, 1, 2});
  pillow.add_face({1, 0, 2});
  EXPECT_EQ(inspect(pillow).non_manifold_edges, 0);
  EXPECT_EQ(inspect(pillow).duplicate_faces, 1);
  EXPECT_EQ(repair(pillow, "x.obj").repairs, std::vector<std::string>{"dropped 1 duplicate face (face 1 duplicates face 0)"});

  PolygonMesh triple = pillow;
  triple.add_face({2, 0, 1});
  triple.positions.push_back({0, 0, 1});
  triple.add_face({1, 0, 3}); // shares an edge with all three copies, repeats none
  EXPECT_EQ(inspect(triple).duplicate_faces, 2);
  const RepairResult r = repair(triple, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"dropped 2 duplicate faces (face 1 duplicates face 0)"});
  EXPECT_EQ(r.mesh.num_faces(), 2);
  expect_repaired(r.mesh);
}

TEST(CheckRepair, RepeatedConsecutiveIndexIsCollapsed) {
  const PolygonMesh m = with_face_replaced(tetrahedron(), 3, {1, 2, 2, 3, 1});
  EXPECT_EQ(strict_error(m), "x.obj: face 3 repeats vertex 2");
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs,
            std::vector<std::string>{"collapsed repeated consecutive vertices in 1 face (face 3 repeats vertex 2)"});
  EXPECT_EQ(r.mesh.face_vertices, tetrahedron().face_vertices);
  expect_repaired(r.mesh);
}

// Collapsing can leave too few vertices, and a vertex repeated apart (a pinched polygon)
// cannot be collapsed: both faces go, and the vertex only they used goes with them.
TEST(CheckRepair, DegenerateFacesAreDropped) {
  PolygonMesh m = tetrahedron();
  m.positions.push_back({5, 5, 5});
  m.add_face({0, 1, 1});
  m.add_face({0, 4, 1, 4});
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, (std::vector<std::string>{"dropped 2 degenerate faces (face 4 repeats vertex 1)",
                                                 "dropped 1 unreferenced vertex (first: vertex 4)"}));
  EXPECT_EQ(r.mesh.face_vertices, tetrahedron().face_vertices);
  expect_repaired(r.mesh);
}

// Past a few vertices repeats are found with a per-vertex stamp rather than pairwise; a
// repeat far apart in a large polygon must still be seen, and a clean one not flagged.
TEST(CheckRepair, LargePolygonWithARepeatFarApart) {
  PolygonMesh m;
  for (int i = 0; i < 12; ++i)
    m.positions.push_back({float(std::cos(i * std::numbers::pi / 6)), float(std::sin(i * std::numbers::pi / 6)), 0});
  m.add_face({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});
  m.add_face({11, 10, 9, 8, 7, 6, 5, 4, 3, 10, 2, 1}); // repeats 10, not consecutively
  EXPECT_EQ(inspect(m).degenerate_faces, 1);
  EXPECT_EQ(strict_error(m), "x.obj: face 1 repeats vertex 10");
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"dropped 1 degenerate face (face 1 repeats vertex 10)"});
  EXPECT_EQ(r.mesh.num_faces(), 1);
  expect_repaired(r.mesh);
}

TEST(CheckRepair, UnreferencedVerticesAreDroppedInOrder) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {9, 9, 9}, {0, 1, 0}, {8, 8, 8}, {0, 0, 1}};
  for (auto f : {std::array{0, 3, 1}, std::array{0, 1, 5}, std::array{0, 5, 3}, std::array{1, 3, 5}}) m.add_face(f);
  EXPECT_EQ(strict_error(m), "x.obj: 2 vertices are not used by any face (first: 2)");
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"dropped 2 unreferenced vertices (first: vertex 2)"});
  EXPECT_EQ(r.mesh.positions, tetrahedron().positions);
  EXPECT_EQ(r.mesh.face_vertices, tetrahedron().face_vertices);
}

TEST(CheckRepair, NanPositionIsRefused) {
  PolygonMesh m = tetrahedron();
  m.positions[3].y = NAN;
  try {
    repair(m, "x.obj");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "x.obj: vertex 3 has a non-finite position (0, nan, 1)");
  }
}

// The server's guard: a mesh above the limit is refused before any work, one at the
// limit is repaired as usual.
TEST(CheckRepair, MaxFacesRefusesLargerMeshes) {
  try {
    repair(cube(), "x.obj", {.max_faces = 5});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "x.obj: 6 faces, more than the limit of 5");
  }
  EXPECT_EQ(repair(cube(), "x.obj", {.max_faces = 6}).mesh.num_faces(), 6);
}

// A NaN no face uses does no harm: it is dropped like any unused vertex.
TEST(CheckRepair, UnusedNanPositionIsDropped) {
  PolygonMesh m = tetrahedron();
  m.positions.push_back({NAN, 0, 0});
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, std::vector<std::string>{"dropped 1 unreferenced vertex (first: vertex 4)"});
  expect_repaired(r.mesh);
}

TEST(CheckRepair, OutOfRangeIndexIsRefused) {
  const PolygonMesh m = with_face_replaced(tetrahedron(), 3, {1, 2, 9});
  try {
    repair(m, "x.obj");
    FAIL() << "no error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(std::string(e.what()), "x.obj: face 3 references vertex 9 but the mesh has 4 vertices");
  }
  EXPECT_THROW(repair(with_face_replaced(tetrahedron(), 0, {-1, 2, 1}), "x.obj"), TopologyError);
}

TEST(CheckRepair, NoFacesLeftIsRefused) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}};
  m.add_face({0, 1, 0});
  EXPECT_EQ(strict_error(m), "x.obj: face 0 repeats vertex 0");
  try {
    repair(m, "x.obj");
    FAIL() << "no error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(std::string(e.what()), "x.obj: no faces left after repair (all 1 face was degenerate or duplicates)");
  }
  EXPECT_THROW(repair(PolygonMesh{}, "x.obj"), TopologyError);
}

// Zero-area faces stay: dropping one would open a hole in the surface.
TEST(CheckRepair, ZeroAreaFaceIsKept) {
  PolygonMesh m = strip(1);
  m.positions.push_back({0.5f, 0, 0});
  m.add_face({0, 4, 1});
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.mesh.num_faces(), 3);
  EXPECT_EQ(inspect(r.mesh).zero_area_faces, 1);
}

// Every repair at once, in order: the face numbers in the lines are those of the input.
TEST(CheckRepair, RepairsComeInOrderAndNameInputFaces) {
  PolygonMesh m = strip(3);
  m.add_face({0, 0, 5});                               // face 6: dropped as degenerate
  m.add_face({5, 1, 0});                               // face 7: duplicate of face 0
  m.positions.push_back({7, 7, 7});                    // vertex 8: unused
  m = with_face_replaced(m, 4, {2, 7, 3});             // face 4 flipped
  const RepairResult r = repair(m, "x.obj");
  EXPECT_EQ(r.repairs, (std::vector<std::string>{"dropped 1 degenerate face (face 6 repeats vertex 0)",
                                                 "dropped 1 duplicate face (face 7 duplicates face 0)",
                                                 "re-oriented 1 face to agree with their neighbours (first: face 4)",
                                                 "dropped 1 unreferenced vertex (first: vertex 8)"}));
  expect_repaired(r.mesh);
  EXPECT_NEAR(total_area(r.mesh), total_area(strip(3)), 1e-9);
}

// ---------------------------------------------------------------- real meshes

// Facts from ../shared/meshes/INDEX.md. genus -1: non-manifold; cross-caps for the Möbius
// band. reoriented: "faces wound against neighbours", which repair must flip. dup:
// duplicate faces, which INDEX does not list.
struct MeshFacts {
  const char* file;
  int32_t vertices, used, faces, edges, boundary_edges, boundary_loops, non_manifold_edges, non_manifold_vertices;
  int32_t zero_area, duplicates, components, genus;
  bool orientable;
  int32_t reoriented;
};

const MeshFacts kMeshes[] = {
    // file                              V      used   F      E       bd   loops nmE nmV zero dup comp genus orient reor
    {"bunny_closed.off",                 34835, 34835, 69666, 104499, 0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"spot_triangulated.obj",            2930,  2930,  5856,  8784,   0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"spot_quadrangulated.obj",          2930,  2930,  2928,  5856,   0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"spot_control_mesh.obj",            188,   188,   180,   366,    0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"tetrahedron.obj",                  4,     4,     4,     6,      0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"icosahedron_binary.stl",           12,    12,    20,    30,     0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"sphere.obj",                       642,   642,   1280,  1920,   0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"torus.obj",                        2304,  2304,  4608,  6912,   0,   0,    0,  0,  0,   0,  1,   1,    true,  0},
    {"kitten.off",                       10000, 10000, 20000, 30000,  0,   0,    0,  0,  0,   0,  1,   1,    true,  0},
    {"bob_small.ply",                    250,   250,   500,   750,    0,   0,    0,  0,  0,   0,  1,   1,    true,  0},
    {"eight.off",                        766,   766,   1536,  2304,   0,   0,    0,  0,  0,   0,  1,   2,    true,  0},
    {"genus3hexa1.obj",                  161,   161,   82,    247,    0,   0,    0,  0,  0,   0,  1,   3,    true,  0},
    {"fertility.off",                    4494,  4494,  9000,  13500,  0,   0,    0,  0,  0,   0,  1,   4,    true,  0},
    {"fandisk_quads.off",                766,   766,   764,   1528,   0,   0,    0,  0,  0,   0,  1,   0,    true,  0},
    {"stanford-bunny_original_holes.obj", 35947, 34834, 69451, 104288, 223, 5,    0,  0,  0,   0,  1,   0,    true,  0},
    {"face.obj",                         25905, 25905, 51712, 77616,  96,  1,    0,  0,  0,   0,  1,   0,    true,  0},
    {"grid.off",                         145,   145,   256,   400,    32,  1,    0,  0,  0,   0,  1,   0,    true,  0},
    {"camelhead.off",                    11381, 11381, 22704, 34084,  56,  1,    0,  0,  0,   0,  1,   0,    true,  0},
    // INDEX counts one component: its two icosahedra touch at a vertex, not along an edge.
    {"hourglass_ico.obj",                23,    23,    40,    60,     0,   0,    0,  1,  0,   0,  2,   -1,   true,  0},
    {"triple_vierbein.obj",              75,    75,    108,   182,    60,  1,    20, 21, 0,   0,  1,   -1,   true,  10},
    {"platonic_shelf.obj",               50,    50,    50,    90,     0,   0,    0,  0,  0,   0,  5,   0,    true,  0},
    {"degtri_four.off",                  5,     5,     4,     8,      4,   1,    0,  0,  1,   0,  1,   0,    true,  0},
    // INDEX's 2170 faces wound against their neighbours (and their stored normals) are the
    // 2167 that repair flips plus one face of each of three double-sided fins (a triangle
    // stored twice on one edge of the surface): repair drops the second copy and cuts
    // the first loose.
    {"conrod.stl",                       3223,  3223,  6442,  9660,   0,   0,    3,  6,  0,   3,  1,   -1,   true,  2167},
    {"beveledcube.obj",                  24,    24,    26,    48,     0,   0,    0,  0,  0,   0,  1,   0,    true,  4},
    {"moebius.obj",                      280,   280,   224,   504,    112, 1,    0,  0,  0,   0,  1,   1,    false, 0},
};

class CheckRealMesh : public ::testing::TestWithParam<MeshFacts> {};

TEST_P(CheckRealMesh, InspectMatchesIndexAndRepairKeepsTheSurface) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const MeshFacts& x = GetParam();
  const PolygonMesh mesh = read_mesh(test::shared_meshes() / x.file);

  const MeshReport r = inspect(mesh);
  EXPECT_EQ(r.vertices, x.vertices);
  EXPECT_EQ(r.vertices - r.unreferenced_vertices, x.used);
  EXPECT_EQ(r.faces, x.faces);
  EXPECT_EQ(r.edges, x.edges);
  EXPECT_EQ(r.boundary_edges, x.boundary_edges);
  EXPECT_EQ(r.boundary_loops, x.boundary_loops);
  EXPECT_EQ(r.non_manifold_edges, x.non_manifold_edges);
  EXPECT_EQ(r.non_manifold_vertices, x.non_manifold_vertices);
  EXPECT_EQ(r.zero_area_faces, x.zero_area);
  EXPECT_EQ(r.degenerate_faces, 0);
  EXPECT_EQ(r.duplicate_faces, x.duplicates);
  EXPECT_EQ(r.non_finite_positions, 0);
  EXPECT_EQ(r.out_of_range_indices, 0);
  EXPECT_EQ(r.orientable, x.orientable);
  ASSERT_EQ(int32_t(r.components.size()), x.components);
  int64_t faces = 0, edges = 0;
  for (const ComponentReport& k : r.components) {
    EXPECT_EQ(k.genus, x.genus);
    EXPECT_EQ(k.orientable, x.orientable);
    faces += k.faces;
    edges += k.edges;
  }
  EXPECT_EQ(faces, x.faces);
  EXPECT_EQ(edges, x.edges);
  if (x.genus >= 0) {
    int64_t chi = 0;
    for (const ComponentReport& k : r.components) chi += k.euler_characteristic;
    EXPECT_EQ(chi, int64_t(x.used) - x.edges + x.faces);
  }

  const RepairResult fixed = repair(mesh, x.file);
  expect_repaired(fixed.mesh);
  EXPECT_EQ(repair_count(fixed, "re-oriented "), x.reoriented);
  EXPECT_EQ(fixed.mesh.num_faces(), x.faces - x.duplicates);
  EXPECT_NEAR(total_area(fixed.mesh), area_without_duplicates(mesh), 1e-9 * total_area(mesh));
  const MeshReport after = inspect(fixed.mesh);
  EXPECT_GE(after.vertices, x.used); // unused vertices go, copies of split vertices come
  EXPECT_GE(after.boundary_edges, x.boundary_edges);
  if (x.non_manifold_vertices == 0) {
    EXPECT_EQ(after.vertices, x.used);
    EXPECT_EQ(after.boundary_loops, x.boundary_loops);
    ASSERT_EQ(after.components.size(), r.components.size());
    for (size_t k = 0; k < r.components.size(); ++k) EXPECT_EQ(after.components[k].genus, r.components[k].genus);
  }
  if (x.non_manifold_vertices == 0 && x.reoriented == 0 && x.used == x.vertices) {
    EXPECT_TRUE(fixed.repairs.empty());
  }
  EXPECT_EQ(fixed.notices.size(), x.orientable ? 0u : 1u);
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, CheckRealMesh, ::testing::ValuesIn(kMeshes),
                         [](const ::testing::TestParamInfo<MeshFacts>& mesh) { return test::test_name(mesh.param.file); });

// Strict mode refuses the broken meshes with the first problem, named after the file.
TEST(CheckRepairStrict, RealMeshesMessages) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto strict_message = [](const char* file) { return strict_error(read_mesh(test::shared_meshes() / file), file); };
  EXPECT_EQ(strict_message("bunny_closed.off"), "(no error)");
  EXPECT_EQ(strict_message("moebius.obj"), "(no error)");
  EXPECT_EQ(strict_message("hourglass_ico.obj"),
            "hourglass_ico.obj: vertex 22 joins 2 separate fans of faces: mesh is not manifold");
  EXPECT_EQ(strict_message("conrod.stl"), "conrod.stl: face 535 duplicates face 534");
  EXPECT_EQ(strict_message("triple_vierbein.obj"),
            "triple_vierbein.obj: edge (0,1) is shared by 3 faces: mesh is not manifold");
  EXPECT_EQ(strict_message("beveledcube.obj"),
            "beveledcube.obj: faces 1 and 13 disagree in orientation across edge (4,7)");
  EXPECT_EQ(strict_message("stanford-bunny_original_holes.obj"),
            "stanford-bunny_original_holes.obj: 1113 vertices are not used by any face (first: 8)");
}

} // namespace
} // namespace meander
