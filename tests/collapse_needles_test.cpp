#include "meander/collapse_needles.h"

#include "test_support.h"

#include "meander/check.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace meander::test {
namespace {

int needles(const PolygonMesh& mesh, double degrees) {
  int count = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto angles = triangle_angles_degrees(mesh, f);
    count += *std::min_element(angles.begin(), angles.end()) < degrees;
  }
  return count;
}

// The grid's interior vertex `v` moved to 1% of the spacing from its neighbour along
// x: the two triangles on the edge between them become needles (0.6 degrees).
PolygonMesh grid_with_needles(int32_t& v, int32_t& w) {
  PolygonMesh mesh = grid(200); // 10 x 10 squares, 11 x 11 vertices
  v = 5 * 11 + 5, w = v + 1;
  mesh.positions[size_t(v)] = mesh.positions[size_t(w)] * 0.99f + mesh.positions[size_t(v)] * 0.01f;
  return mesh;
}

TEST(CollapseNeedles, MergesTheEndsOfANeedlesShortEdge) {
  int32_t v = 0, w = 0;
  const PolygonMesh mesh = grid_with_needles(v, w);
  ASSERT_EQ(needles(mesh, 5), 2);
  const NeedleCollapses collapsed = collapse_needles(mesh);
  EXPECT_EQ(collapsed.collapses, 1);
  EXPECT_EQ(needles(collapsed.mesh, 5), 0);
  EXPECT_EQ(collapsed.mesh.num_faces(), mesh.num_faces() - 2);
  ASSERT_EQ(collapsed.mesh.num_vertices(), mesh.num_vertices() - 1);
  // The merged vertex is the edge's midpoint; the others keep their place and order.
  const Vec3 midpoint = (mesh.positions[size_t(v)] + mesh.positions[size_t(w)]) * 0.5f;
  EXPECT_LT(norm(collapsed.mesh.positions[size_t(v)] - midpoint), 1e-6);
  for (int32_t i = 0; i < collapsed.mesh.num_vertices(); ++i) {
    if (i != v) {
      EXPECT_EQ(collapsed.mesh.positions[size_t(i)], mesh.positions[size_t(i < w ? i : i + 1)]) << i;
    }
  }
  const MeshReport report = inspect(collapsed.mesh);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_EQ(report.non_manifold_edges, 0);
  EXPECT_EQ(report.non_manifold_vertices, 0);
  EXPECT_EQ(report.misoriented_edges, 0);
  ASSERT_EQ(report.components.size(), 1u);
  EXPECT_EQ(report.components[0].euler_characteristic, 1);
}

// The collapse would leave two faces with the same corners (a tetrahedron's), or pinch
// the surface where both ends lie on the boundary but the edge does not: refused.
TEST(CollapseNeedles, KeepsTheMeshManifold) {
  PolygonMesh tetrahedron;
  tetrahedron.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.001f, 0.001f, 0.01f}};
  for (const auto& f : {std::array{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}) tetrahedron.add_face(f);
  ASSERT_GT(needles(tetrahedron, 5), 0);
  EXPECT_EQ(collapse_needles(tetrahedron).collapses, 0);

  // A square pinched at its waist: the edge B-T joins the top and bottom boundaries.
  PolygonMesh waist;
  waist.positions = {{-1, -1, 0}, {-1, 1, 0}, {0, 0.005f, 0}, {0, -0.005f, 0}, {1, -1, 0}, {1, 1, 0}};
  for (const auto& f : {std::array{0, 3, 2}, {0, 2, 1}, {3, 4, 5}, {3, 5, 2}}) waist.add_face(f);
  ASSERT_GT(needles(waist, 5), 0);
  EXPECT_EQ(collapse_needles(waist).collapses, 0);
}

// A triangle turned over (one corner pushed across the opposite edge) faces against
// all its neighbours whatever its angles: a scan's fold. It goes, with its neighbour
// across its shortest edge, and every face then faces up.
TEST(CollapseNeedles, RemovesATriangleFoldedOverItsNeighbours) {
  PolygonMesh mesh = grid(200);
  // The grid's squares are split along one diagonal; find an interior triangle and push
  // the corner opposite its longest side just across that side.
  int32_t folded = -1;
  for (int32_t f = 0; f < mesh.num_faces() && folded < 0; ++f) {
    const auto t = mesh.face(f);
    bool inside = true;
    for (const int32_t v : t) {
      const Vec3 p = mesh.positions[size_t(v)];
      inside = inside && p.x > 0.15f && p.x < 0.85f && p.y > 0.15f && p.y < 0.85f;
    }
    if (inside) folded = f;
  }
  ASSERT_GE(folded, 0);
  const auto t = mesh.face(folded);
  int k = 0; // the corner facing the longest side
  double longest = 0;
  for (int i = 0; i < 3; ++i) {
    const double side = norm(mesh.positions[size_t(t[size_t((i + 1) % 3)])] - mesh.positions[size_t(t[size_t((i + 2) % 3)])]);
    if (side > longest) longest = side, k = i;
  }
  const Vec3 a = mesh.positions[size_t(t[size_t((k + 1) % 3)])], b = mesh.positions[size_t(t[size_t((k + 2) % 3)])];
  Vec3& c = mesh.positions[size_t(t[size_t(k)])];
  const Vec3 middle = (a + b) * 0.5f;
  c = middle + (middle - c) * 0.1f; // across a-b, a tenth as far
  auto facing_down = [](const PolygonMesh& m) {
    int count = 0;
    for (int32_t f = 0; f < m.num_faces(); ++f) {
      const auto v = m.face(f);
      count += cross(m.positions[size_t(v[1])] - m.positions[size_t(v[0])], m.positions[size_t(v[2])] - m.positions[size_t(v[0])]).z < 0;
    }
    return count;
  };
  ASSERT_EQ(facing_down(grid(200)), 0);
  ASSERT_EQ(facing_down(mesh), 1);
  const NeedleCollapses collapsed = collapse_needles(mesh);
  EXPECT_GE(collapsed.collapses, 1);
  EXPECT_EQ(facing_down(collapsed.mesh), 0);
  const MeshReport report = inspect(collapsed.mesh);
  EXPECT_EQ(report.non_manifold_edges + report.non_manifold_vertices + report.misoriented_edges, 0);
  EXPECT_EQ(report.boundary_loops, 1);
}

// On a non-orientable surface faces may be wound either way: a face wound against its
// neighbours but lying flat among them is no fold.
TEST(CollapseNeedles, WindingAloneIsNoFold) {
  PolygonMesh mesh = grid(200);
  int32_t* face = mesh.face_vertices.data() + mesh.face_start[100];
  std::swap(face[1], face[2]);
  EXPECT_EQ(collapse_needles(mesh).collapses, 0);
}

TEST(CollapseNeedles, WellShapedMeshesAreUnchanged) {
  for (const PolygonMesh& mesh : {sphere(2000), torus(2000), grid(500), genus_surface(2, 3000)}) {
    const NeedleCollapses collapsed = collapse_needles(mesh);
    EXPECT_EQ(collapsed.collapses, 0);
    EXPECT_EQ(collapsed.mesh.positions, mesh.positions);
    EXPECT_EQ(collapsed.mesh.face_vertices, mesh.face_vertices);
  }
}

// A cap's short sides are long (here half its long side): merging them would move the
// surface that far, and caps are the flips' (flip_caps.h).
TEST(CollapseNeedles, LeavesCaps) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {1, 0.02f, 0}, {1, -1, 0}, {1, 1, 0}};
  for (const auto& f : {std::array{0, 1, 2}, {1, 0, 3}, {0, 2, 4}, {2, 1, 4}}) mesh.add_face(f);
  ASSERT_GT(needles(mesh, 5), 0);
  EXPECT_EQ(collapse_needles(mesh).collapses, 0);
}

} // namespace
} // namespace meander::test
