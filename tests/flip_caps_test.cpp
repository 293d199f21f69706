#include "meander/flip_caps.h"

#include "test_support.h"

#include "meander/check.h"
#include "meander/io.h"
#include "meander/remesh.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace meander::test {
namespace {

double largest_angle_degrees(const PolygonMesh& mesh, int32_t f) {
  const auto angles = triangle_angles_degrees(mesh, f);
  return *std::max_element(angles.begin(), angles.end());
}

int caps(const PolygonMesh& mesh, double degrees) {
  int count = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) count += mesh.face_size(f) == 3 && largest_angle_degrees(mesh, f) > degrees;
  return count;
}

// Triangle (a, b, c) is a cap, c almost on the edge a-b; (b, a, d) its neighbour.
PolygonMesh cap_pair(Vec3 d) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {1, 0.05f, 0}, d};
  mesh.add_face({0, 1, 2});
  mesh.add_face({1, 0, 3});
  return mesh;
}

TEST(FlipCaps, FlipsTheLongEdgeOfACap) {
  const CapFlips flipped = flip_caps(cap_pair({1, -1, 0}));
  EXPECT_EQ(flipped.flips, 1);
  ASSERT_EQ(flipped.mesh.num_faces(), 2);
  EXPECT_GT(largest_angle_degrees(cap_pair({1, -1, 0}), 0), 170);
  for (int32_t f = 0; f < 2; ++f) {
    const auto v = flipped.mesh.face(f);
    EXPECT_NE(std::find(v.begin(), v.end(), 2), v.end()) << "every new triangle has the cap's apex";
    EXPECT_NE(std::find(v.begin(), v.end(), 3), v.end()) << "and the far corner";
    EXPECT_LT(largest_angle_degrees(flipped.mesh, f), 100);
  }
  const MeshReport report = inspect(flipped.mesh);
  EXPECT_EQ(report.misoriented_edges, 0);
  EXPECT_EQ(report.non_manifold_edges, 0);
  EXPECT_EQ(report.boundary_loops, 1);
}

// Folded along the cap's long edge, the flip would cut the crease's corner off unless
// the cap is flat enough.
TEST(FlipCaps, LeavesACreaseAlone) {
  PolygonMesh folded = cap_pair({1, 0, -1});
  EXPECT_EQ(flip_caps(folded).flips, 1); // the cap's apex 0.05 from the edge: moves 2.4% of it
  folded.positions[2].y = 0.3f;          // a 147 degree cap: 14%
  EXPECT_EQ(flip_caps(folded).flips, 0);
  EXPECT_EQ(flip_caps(folded, {.max_move = 0.2}).flips, 1);
}

// A flat pair that is not convex: the flip would lay one new triangle over the other.
TEST(FlipCaps, NeverFoldsATriangleOver) {
  EXPECT_EQ(flip_caps(cap_pair({4, -0.03f, 0})).flips, 0);
}

TEST(FlipCaps, LeavesMisorientedAndMixedPairsAlone) {
  PolygonMesh misoriented = cap_pair({1, -1, 0});
  std::swap(misoriented.face_vertices[3], misoriented.face_vertices[4]); // (a, b, d): both faces run a -> b
  EXPECT_EQ(flip_caps(misoriented).flips, 0);
  PolygonMesh with_quad;
  with_quad.positions = {{0, 0, 0}, {2, 0, 0}, {1, 0.05f, 0}, {2, -1, 0}, {0, -1, 0}};
  with_quad.add_face({0, 1, 2});
  with_quad.add_face({1, 0, 4, 3});
  EXPECT_EQ(flip_caps(with_quad).flips, 0);
}

// CGAL's degtri_four: a triangle with collinear corners along the boundary, fanned
// around its middle corner. Cut off, it leaves the boundary running through that corner.
TEST(FlipCaps, CutsACapOffTheBoundary) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 1, 0}};
  for (const auto& f : {std::array{0, 1, 2}, std::array{0, 2, 3}, std::array{2, 1, 4}, std::array{3, 2, 4}}) mesh.add_face(f);
  const CapFlips cut = flip_caps(mesh);
  EXPECT_EQ(cut.flips, 0);
  EXPECT_EQ(cut.cuts, 1);
  ASSERT_EQ(cut.mesh.num_faces(), 3);
  EXPECT_EQ(cut.mesh.positions, mesh.positions);
  const MeshReport report = inspect(cut.mesh);
  EXPECT_EQ(report.non_manifold_vertices, 0);
  EXPECT_EQ(report.unreferenced_vertices, 0);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_EQ(caps(cut.mesh, 120), 0);
  // A lone cap: its apex is on the boundary already.
  PolygonMesh lone;
  lone.positions = {{0, 0, 0}, {2, 0, 0}, {1, 0.05f, 0}};
  lone.add_face({0, 1, 2});
  EXPECT_EQ(flip_caps(lone).cuts, 0);
}

// A tetrahedron whose apex lies almost on an edge: the flip would make an edge it already
// has (and two faces on the same three vertices).
TEST(FlipCaps, NeverMakesAnEdgeTheMeshHas) {
  PolygonMesh tet;
  tet.positions = {{0, 0, 0}, {2, 0, 0}, {1, 0.05f, 0}, {1, -1, 0.1f}};
  for (const auto& f : {std::array{0, 1, 2}, std::array{1, 0, 3}, std::array{2, 1, 3}, std::array{0, 2, 3}}) tet.add_face(f);
  const CapFlips flipped = flip_caps(tet);
  EXPECT_EQ(flipped.flips, 0);
  EXPECT_EQ(flipped.mesh.face_vertices, tet.face_vertices);
}

TEST(FlipCaps, WellShapedMeshesAreUnchanged) {
  for (const PolygonMesh& mesh : {torus(2000), make_shape("pretzel", 3000)}) {
    ASSERT_EQ(caps(mesh, 120), 0);
    const CapFlips flipped = flip_caps(mesh);
    EXPECT_EQ(flipped.flips, 0);
    EXPECT_EQ(flipped.mesh.face_vertices, mesh.face_vertices);
  }
}

// The Stanford bunny with its holes: a scan whose flat caps fold a variable wire's slabs.
// The flips keep it a manifold of the same topology and faces, its vertices where they
// were, and remove most of its caps.
TEST(FlipCaps, KeepsAScanManifoldAndRemovesMostCaps) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const PolygonMesh bunny = repair(read_mesh(shared_meshes() / "stanford-bunny_original_holes.obj"), "bunny").mesh;
  const CapFlips flipped = flip_caps(bunny);
  EXPECT_GT(flipped.flips, 100);
  EXPECT_EQ(flipped.mesh.positions, bunny.positions);
  EXPECT_EQ(flipped.mesh.face_start, bunny.face_start);
  const MeshReport before = inspect(bunny), after = inspect(flipped.mesh);
  EXPECT_EQ(after.non_manifold_edges, 0);
  EXPECT_EQ(after.non_manifold_vertices, 0);
  EXPECT_EQ(after.misoriented_edges, 0);
  EXPECT_EQ(after.boundary_loops, before.boundary_loops);
  ASSERT_EQ(after.components.size(), before.components.size());
  EXPECT_EQ(after.components[0].euler_characteristic, before.components[0].euler_characteristic);
  // 327 -> 27 triangles with an angle over 120 degrees, 18 -> 0 over 150.
  EXPECT_LT(caps(flipped.mesh, 120), caps(bunny, 120) / 4);
  EXPECT_LT(caps(flipped.mesh, 150), caps(bunny, 150) / 4);
  EXPECT_NEAR(surface_area(flipped.mesh), surface_area(bunny), 1e-3 * surface_area(bunny));
  EXPECT_EQ(flip_caps(bunny).mesh.face_vertices, flipped.mesh.face_vertices) << "deterministic";
}

} // namespace
} // namespace meander::test
