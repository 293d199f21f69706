#include "meander/connectivity.h"

#include "meander/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>

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
  EXPECT_TRUE(std::is_sorted(c.edge_vertices.begin(), c.edge_vertices.end()));
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

// A vertex of high valence (a fan of 200 triangles around vertex 0) takes the sort
// path for long ranges; every spoke edge must still be found with both its faces.
TEST(Connectivity, HighValenceFan) {
  PolygonMesh m;
  m.positions.resize(202);
  for (int32_t i = 1; i <= 200; ++i) m.add_face({0, i, i % 200 + 1});
  const Connectivity c = build_connectivity(m);
  EXPECT_EQ(c.num_edges(), 400);
  int spokes = 0;
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_vertices[e][0] == 0) {
      ++spokes;
      EXPECT_EQ(c.edge_degree(e), 2);
      for (int32_t h : c.halfedges(e)) EXPECT_EQ(c.halfedge_edge[h], e);
    }
  EXPECT_EQ(spokes, 200);
  EXPECT_TRUE(std::is_sorted(c.edge_vertices.begin(), c.edge_vertices.end()));
}

// Against a plain reference (a std::map from the vertex pair to its halfedges), on a mesh
// large enough to span several of the parallel vertex blocks and with its faces shuffled
// so that the threads' placement order varies.
TEST(Connectivity, MatchesAMapReferenceOnALargeShuffledMesh) {
  const PolygonMesh sorted_faces = sphere(300000);
  PolygonMesh m;
  m.positions = sorted_faces.positions;
  const int64_t n = sorted_faces.num_faces();
  ASSERT_EQ(std::gcd(int64_t(7919), n), 1); // so i -> 7919 i mod n is a permutation
  for (int64_t i = 0; i < n; ++i) m.add_face(sorted_faces.face(int32_t(i * 7919 % n)));
  ASSERT_GT(m.num_vertices(), 3 * 32768);

  std::map<std::array<int32_t, 2>, std::vector<int32_t>> reference;
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const auto v = m.face(f);
    for (size_t i = 0; i < v.size(); ++i) {
      const int32_t a = v[i], b = v[(i + 1) % v.size()];
      reference[{std::min(a, b), std::max(a, b)}].push_back(m.face_start[f] + int32_t(i));
    }
  }
  const Connectivity c = build_connectivity(m);
  ASSERT_EQ(size_t(c.num_edges()), reference.size());
  int32_t e = 0;
  for (const auto& [ends, halfedges] : reference) {
    ASSERT_EQ(c.edge_vertices[size_t(e)], ends);
    ASSERT_EQ(std::vector<int32_t>(c.halfedges(e).begin(), c.halfedges(e).end()), halfedges);
    for (int32_t h : halfedges) {
      ASSERT_EQ(c.halfedge_edge[size_t(h)], e);
      ASSERT_EQ(m.face_start[c.face_of(h)] <= h && h < m.face_start[c.face_of(h) + 1], true);
    }
    ++e;
  }
}

// A mesh of one face size names faces by division and keeps no halfedge_face; a mixed
// one keeps it. Either way every halfedge's face and successor agree with face_start.
TEST(Connectivity, FaceOfEveryHalfedgeWithAndWithoutTheArray) {
  const auto expect_faces = [](const PolygonMesh& m, int32_t face_size) {
    const Connectivity c = build_connectivity(m);
    EXPECT_EQ(c.face_size, face_size);
    EXPECT_EQ(c.halfedge_face.size(), face_size > 0 ? 0 : size_t(m.num_corners()));
    for (int32_t f = 0; f < m.num_faces(); ++f)
      for (int32_t h = m.face_start[f]; h < m.face_start[f + 1]; ++h) {
        ASSERT_EQ(c.face_of(h), f) << "halfedge " << h;
        ASSERT_EQ(next_halfedge(m, c, h), h + 1 == m.face_start[f + 1] ? m.face_start[f] : h + 1) << "halfedge " << h;
      }
  };
  PolygonMesh m;
  for (int i = 0; i < 12; ++i) m.positions.push_back({float(i), float(i * i % 7), 0});
  for (const int size : {3, 4, 5}) {
    SCOPED_TRACE(size);
    PolygonMesh uniform = m;
    for (int32_t f = 0; f < 4; ++f) {
      std::vector<int32_t> face;
      for (int k = 0; k < size; ++k) face.push_back((2 * f + k) % 12);
      uniform.add_face(face);
    }
    expect_faces(uniform, size);
    PolygonMesh mixed = uniform;
    mixed.add_face({0, 5, 9});
    expect_faces(mixed, size == 3 ? 3 : 0);
    mixed.add_face({1, 3, 8, 10});
    expect_faces(mixed, 0);
  }
  expect_faces(sphere(300000), 3);
  expect_faces(PolygonMesh{}, 0);
}

} // namespace
} // namespace meander
