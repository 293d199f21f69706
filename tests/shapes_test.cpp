#include "meander/shapes.h"

#include "meander/connectivity.h"
#include "meander/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

namespace meander {
namespace {

struct Topology {
  int64_t chi;
  int boundary_edges;
};

Topology topology(const PolygonMesh& m) {
  const Connectivity c = build_connectivity(m);
  int boundary = 0;
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    EXPECT_LE(c.edge_degree(e), 2);
    boundary += c.edge_degree(e) == 1;
  }
  return {int64_t(m.num_vertices()) - c.num_edges() + m.num_faces(), boundary};
}

// The generated shapes have the topology their names promise (chi = 2 - 2g for closed
// surfaces), and about the number of faces asked for.
TEST(Shapes, TopologyAndSize) {
  EXPECT_EQ(topology(sphere(1000)).chi, 2);
  EXPECT_EQ(topology(torus(1000)).chi, 0);
  for (int g = 0; g <= 3; ++g) {
    const PolygonMesh m = genus_surface(g, 3000);
    const Topology t = topology(m);
    EXPECT_EQ(t.chi, 2 - 2 * g) << "genus " << g;
    EXPECT_EQ(t.boundary_edges, 0);
    EXPECT_GT(m.num_faces(), 3000 / 3);
    EXPECT_LT(m.num_faces(), 3000 * 3);
  }
  EXPECT_EQ(topology(grid(800)).chi, 1);
  EXPECT_GT(topology(grid(800)).boundary_edges, 0);
  EXPECT_EQ(topology(moebius(200)).chi, 0);
  for (int64_t n : {int64_t(100), int64_t(10000)}) {
    EXPECT_NEAR(double(sphere(n).num_faces()), double(n), 0.2 * double(n));
    EXPECT_NEAR(double(torus(n).num_faces()), double(n), 0.2 * double(n));
  }
}

// The pretzel is OpenSubdiv's limit surface: a real surface, not collapsed points (a
// refinement without full topology in the last level makes Limit() fail and leaves
// zeros), with no zero-length edge.
TEST(Shapes, PretzelIsALimitSurfaceWithoutCollapsedEdges) {
  const PolygonMesh m = genus_surface(2, 2000);
  const Box3 box = bounding_box(m.positions);
  EXPECT_GT(box.max.x - box.min.x, 4);
  EXPECT_GT(box.max.y - box.min.y, 2);
  EXPECT_GT(box.max.z - box.min.z, 0.5);
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const auto v = m.face(f);
    for (size_t i = 0; i < v.size(); ++i)
      ASSERT_GT(norm(m.positions[size_t(v[i])] - m.positions[size_t(v[(i + 1) % v.size()])]), 1e-4) << "face " << f;
  }
}

// A shuffled mesh is the same surface: every face keeps its corners' positions in order,
// the topology is unchanged, and the seed fixes the order.
TEST(Shapes, ShuffledIsTheSameSurfaceInAnotherOrder) {
  const PolygonMesh mesh = moebius(300); // quads, with boundary and no orientation
  const PolygonMesh a = shuffled(mesh, 7), b = shuffled(mesh, 7), c = shuffled(mesh, 8);
  ASSERT_EQ(a.num_faces(), mesh.num_faces());
  ASSERT_EQ(a.num_vertices(), mesh.num_vertices());
  EXPECT_EQ(a.face_vertices, b.face_vertices);
  EXPECT_NE(a.face_vertices, c.face_vertices);
  EXPECT_NE(a.face_vertices, mesh.face_vertices);
  const auto corners = [](const PolygonMesh& m) {
    std::vector<std::vector<std::array<float, 3>>> faces;
    for (int32_t f = 0; f < m.num_faces(); ++f) {
      auto& face = faces.emplace_back();
      for (const int32_t v : m.face(f)) face.push_back({m.positions[size_t(v)].x, m.positions[size_t(v)].y, m.positions[size_t(v)].z});
    }
    std::sort(faces.begin(), faces.end());
    return faces;
  };
  EXPECT_EQ(corners(a), corners(mesh));
  EXPECT_EQ(topology(a).chi, topology(mesh).chi);
  EXPECT_EQ(topology(a).boundary_edges, topology(mesh).boundary_edges);
}

TEST(Shapes, RefusesUnknownNamesAndSizes) {
  EXPECT_THROW(make_shape("klein", 100), UsageError);
  EXPECT_THROW(make_shape("sphere", 0), UsageError);
  EXPECT_THROW(genus_surface(-1, 100), UsageError);
}

} // namespace
} // namespace meander
