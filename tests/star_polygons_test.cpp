#include "meander/star_polygons.h"

#include "meander/check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace meander {
namespace {

// A hexagon beside a quad and a triangle: only the hexagon becomes a star.
PolygonMesh mixed() {
  PolygonMesh mesh;
  for (int k = 0; k < 6; ++k) {
    const double a = k * std::numbers::pi / 3;
    mesh.positions.push_back({float(std::cos(a)), float(std::sin(a)), 0});
  }
  mesh.positions.push_back({2, 0, 0});
  mesh.positions.push_back({2, 1, 0});
  mesh.add_face({0, 1, 2, 3, 4, 5});
  mesh.add_face({6, 7, 1, 0});
  mesh.add_face({0, 5, 6});
  return mesh;
}

TEST(StarPolygons, SplitsLargePolygonsAroundTheirCentroids) {
  const PolygonMesh mesh = mixed();
  const StarredPolygons starred = star_polygons(mesh);
  EXPECT_EQ(starred.stars, 1);
  const PolygonMesh& out = starred.mesh;
  ASSERT_EQ(out.num_vertices(), mesh.num_vertices() + 1);
  EXPECT_NEAR(norm(out.positions.back()), 0, 1e-6); // the hexagon's centroid
  ASSERT_EQ(out.num_faces(), 6 + 2);
  for (int32_t f = 0; f < 6; ++f) {
    const auto t = out.face(f);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0], 8);
    EXPECT_EQ(t[1], f);
    EXPECT_EQ(t[2], (f + 1) % 6);
    // Wound as the hexagon was: counter-clockwise seen from +z.
    const Vec3 a = out.positions[size_t(t[0])], b = out.positions[size_t(t[1])], c = out.positions[size_t(t[2])];
    EXPECT_GT(cross(b - a, c - a).z, 0);
  }
  EXPECT_EQ(std::vector<int32_t>(out.face(6).begin(), out.face(6).end()), (std::vector<int32_t>{6, 7, 1, 0}));
  EXPECT_EQ(std::vector<int32_t>(out.face(7).begin(), out.face(7).end()), (std::vector<int32_t>{0, 5, 6}));
  const MeshReport report = inspect(out);
  EXPECT_EQ(report.misoriented_edges, 0);
  EXPECT_EQ(report.non_manifold_edges, 0);
  EXPECT_EQ(report.boundary_loops, 1);
}

TEST(StarPolygons, SmallerFacesAreLeftAsTheyAre) {
  const PolygonMesh mesh = mixed();
  const StarredPolygons kept = star_polygons(mesh, 7);
  EXPECT_EQ(kept.stars, 0);
  EXPECT_EQ(kept.mesh.face_vertices, mesh.face_vertices);
  EXPECT_EQ(kept.mesh.positions, mesh.positions);
  EXPECT_EQ(star_polygons(mesh, 4).stars, 2); // the quad too
}

} // namespace
} // namespace meander
