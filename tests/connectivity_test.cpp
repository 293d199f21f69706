#include "meander/connectivity.h"

#include <gtest/gtest.h>

namespace meander {
namespace {

// Two triangles sharing edge (1,2): one interior edge, four boundary edges.
TEST(Connectivity, TwoTrianglesShareOneEdge) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  m.add_face({0, 1, 2});
  m.add_face({2, 1, 3});
  const Connectivity c = build_connectivity(m);
  ASSERT_EQ(c.num_edges(), 5);
  int interior = 0;
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    EXPECT_LT(c.edge_vertices[e][0], c.edge_vertices[e][1]);
    if (c.edge_degree(e) == 2) {
      ++interior;
      EXPECT_EQ(c.edge_vertices[e], (std::array<int32_t, 2>{1, 2}));
    }
  }
  EXPECT_EQ(interior, 1);
  EXPECT_EQ(c.halfedge_edge[1], c.halfedge_edge[3]); // 1->2 in face 0, 2->1 in face 1
  EXPECT_EQ(halfedge_target(m, c, 2), 0);
}

// Three triangles on one edge: the edge is kept once with degree 3, not dropped.
TEST(Connectivity, NonManifoldEdgeHasDegreeThree) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.add_face({0, 1, 2});
  m.add_face({1, 0, 3});
  m.add_face({0, 1, 4});
  const Connectivity c = build_connectivity(m);
  int degree3 = 0;
  for (int32_t e = 0; e < c.num_edges(); ++e) degree3 += c.edge_degree(e) == 3;
  EXPECT_EQ(degree3, 1);
  EXPECT_EQ(c.num_edges(), 7);
}

} // namespace
} // namespace meander
