#include "meander/quadrangulate.h"

#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

namespace meander {
namespace {

// Side adjacency must be symmetric and only -1 on sides that may be open.
void expect_symmetric(const QuadMesh& q) {
  for (int32_t i = 0; i < q.num_quads(); ++i)
    for (int k = 0; k < 4; ++k) {
      const int32_t n = q.neighbors[size_t(i)][size_t(k)];
      if (n < 0) continue;
      EXPECT_EQ(q.neighbors[size_t(n >> 2)][size_t(n & 3)], 4 * i + k) << "quad " << i << " side " << k;
      // The shared side has the same two vertices.
      const auto& a = q.quads[size_t(i)];
      const auto& b = q.quads[size_t(n >> 2)];
      std::array<int32_t, 2> sa{a[size_t(k)], a[size_t((k + 1) & 3)]}, sb{b[size_t(n & 3)], b[size_t(((n & 3) + 1) & 3)]};
      std::sort(sa.begin(), sa.end());
      std::sort(sb.begin(), sb.end());
      EXPECT_EQ(sa, sb);
    }
}

TEST(DualSimplest, OneQuadPerEdgeWithCornersV1F2V2F1) {
  const PolygonMesh m = torus(200);
  const Connectivity c = build_connectivity(m);
  const QuadMesh q = dual_simplest(m, c);
  EXPECT_EQ(q.num_quads(), c.num_edges());
  EXPECT_EQ(q.positions.size(), size_t(m.num_vertices() + m.num_faces()));
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    const auto& corners = q.quads[size_t(e)];
    EXPECT_LT(corners[0], m.num_vertices());
    EXPECT_GE(corners[1], m.num_vertices());
    EXPECT_LT(corners[2], m.num_vertices());
    EXPECT_GE(corners[3], m.num_vertices());
    std::array<int32_t, 2> ends{corners[0], corners[2]};
    std::sort(ends.begin(), ends.end());
    EXPECT_EQ(ends, c.edge_vertices[size_t(e)]);
  }
  expect_symmetric(q);
  EXPECT_EQ(count_open_sides(q), 0);
}

// The consuming overload builds the same quads and leaves its inputs empty.
TEST(DualSimplest, ConsumingOverloadMatchesAndReleases) {
  PolygonMesh m = moebius(60);
  Connectivity c = build_connectivity(m);
  const QuadMesh copy = dual_simplest(m, c);
  const QuadMesh moved = dual_simplest(std::move(m), std::move(c));
  EXPECT_EQ(moved.positions, copy.positions);
  EXPECT_EQ(moved.quads, copy.quads);
  EXPECT_EQ(moved.neighbors, copy.neighbors);
  EXPECT_EQ(moved.face_point_offset, copy.face_point_offset);
  EXPECT_TRUE(m.face_vertices.empty()); // NOLINT(bugprone-use-after-move): checking the release
  EXPECT_TRUE(c.halfedge_edge.empty()); // NOLINT(bugprone-use-after-move)
}

// On an oriented surface the quads keep its orientation: quad (v1, f2, v2, f1) has the
// normal of face f1.
TEST(DualSimplest, QuadsFollowTheSurfaceOrientation) {
  const PolygonMesh m = sphere(300);
  const QuadMesh q = dual_simplest(m, build_connectivity(m));
  for (const auto& c : q.quads) {
    const Vec3 n = cross(q.positions[size_t(c[1])] - q.positions[size_t(c[3])], q.positions[size_t(c[2])] - q.positions[size_t(c[0])]);
    // Outward normal of the unit sphere at the quad: its centre.
    const Vec3 centre = (q.positions[size_t(c[0])] + q.positions[size_t(c[2])]) * 0.5f;
    EXPECT_GT(dot(n, centre), 0);
  }
}

// A boundary edge makes a half quad (v1, -, v2, f1) whose two existing sides are joined.
TEST(DualSimplest, BoundaryEdgesMakeHalfQuads) {
  const PolygonMesh m = grid(50);
  const Connectivity c = build_connectivity(m);
  const QuadMesh q = dual_simplest(m, c);
  int32_t half = 0, boundary = 0;
  for (int32_t e = 0; e < c.num_edges(); ++e) boundary += c.edge_degree(e) == 1;
  for (int32_t i = 0; i < q.num_quads(); ++i)
    if (q.is_half(i)) {
      ++half;
      EXPECT_EQ(q.neighbors[size_t(i)][0], -1);
      EXPECT_EQ(q.neighbors[size_t(i)][1], -1);
      EXPECT_GE(q.neighbors[size_t(i)][2], 0);
      EXPECT_GE(q.neighbors[size_t(i)][3], 0);
    }
  EXPECT_EQ(half, boundary);
  expect_symmetric(q);
  EXPECT_EQ(count_open_sides(q), 0);
}

// A Möbius band crosses some edge the same way from both faces: the adjacency must still
// pair the right sides.
TEST(DualSimplest, NonOrientableBand) {
  const PolygonMesh m = moebius(40);
  expect_symmetric(dual_simplest(m, build_connectivity(m)));
}

TEST(CatmullClarkQuads, FourQuadsPerTriangleAndTwoColourable) {
  const PolygonMesh m = genus_surface(1, 300);
  const Connectivity c = build_connectivity(m);
  const QuadMesh q = catmull_clark_quads(m, c);
  EXPECT_EQ(q.num_quads(), m.num_corners());
  expect_symmetric(q);
  // Vertex and face points are one colour, edge points the other: every side joins both.
  const int32_t nv = m.num_vertices(), ne = c.num_edges();
  auto is_edge_point = [&](int32_t v) { return v >= nv && v < nv + ne; };
  for (const auto& corners : q.quads)
    for (int k = 0; k < 4; ++k) EXPECT_NE(is_edge_point(corners[size_t(k)]), is_edge_point(corners[size_t((k + 1) & 3)]));
}

TEST(QuadsAsIs, RefusesAFaceThatIsNotAQuad) {
  const PolygonMesh m = sphere(20);
  try {
    quads_as_is(m, build_connectivity(m));
    FAIL();
  } catch (const TopologyError& e) {
    EXPECT_STREQ(e.what(), "face 0 has 3 vertices: quad none needs a mesh of quads only (use quad dual-simplest or catmull-clark)");
  }
}

TEST(DualSimplest, RefusesANonManifoldEdge) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.add_face({0, 1, 2});
  m.add_face({1, 0, 3});
  m.add_face({0, 1, 4});
  try {
    dual_simplest(m, build_connectivity(m));
    FAIL();
  } catch (const TopologyError& e) {
    EXPECT_STREQ(e.what(), "edge (0,1) is shared by 3 faces: mesh is not manifold");
  }
}

} // namespace
} // namespace meander
