#include "meander/check.h"
#include "meander/error.h"
#include "meander/remesh.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace meander {
namespace {

struct Topology {
  size_t components = 0;
  int64_t euler = 0;
  int32_t boundary_loops = 0;
  bool orientable = true;
  friend bool operator==(const Topology&, const Topology&) = default;
};

Topology topology_of(const PolygonMesh& mesh) {
  const MeshReport r = inspect(mesh);
  Topology t{.components = r.components.size(), .orientable = r.orientable};
  for (const ComponentReport& c : r.components) t.euler += c.euler_characteristic, t.boundary_loops += c.boundary_loops;
  return t;
}

std::vector<double> edge_lengths(const PolygonMesh& mesh) {
  std::vector<double> lengths;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto face = mesh.face(f);
    for (size_t i = 0; i < face.size(); ++i)
      lengths.push_back(norm(mesh.positions[size_t(face[(i + 1) % face.size()])] - mesh.positions[size_t(face[i])]));
  }
  std::sort(lengths.begin(), lengths.end());
  return lengths;
}

// Each kind of surface the remeshing must keep: closed of genus 0 to 3, with a
// boundary, non-orientable (cut along a seam and glued back), and two
// components at once.
struct Case {
  const char* name;
  PolygonMesh mesh;
  double edge_length;
};

std::vector<Case> cases() {
  const PolygonMesh two = test::side_by_side(sphere(800), torus(800), {3, 0, 0});
  return {{"sphere", sphere(2000), 0.12},
          {"torus", torus(3000), 0.08},
          {"genus 2", genus_surface(2, 4000), 0.15},
          {"genus 3", genus_surface(3, 6000), 0.15},
          {"grid", grid(2000), 0.05},
          {"moebius", moebius(600), 0.1},
          {"sphere and torus", two, 0.1}};
}

TEST(Remesh, KeepsTheTopologyOfEveryKindOfSurface) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const PolygonMesh result = remesh(c.mesh, {.edge_length = c.edge_length});
    EXPECT_EQ(topology_of(result), topology_of(c.mesh));
    EXPECT_EQ(inspect(result).faces_by_size.at(3),
              result.num_faces()); // all triangles
  }
}

TEST(Remesh, EdgesAreNearTheTargetAndTheFacesNearTheEstimate) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const PolygonMesh result = remesh(c.mesh, {.edge_length = c.edge_length});
    const std::vector<double> lengths = edge_lengths(result);
    const double median = lengths[lengths.size() / 2];
    // CGAL's edges: from 4/5 to 4/3 of the target, most shorter
    EXPECT_GT(median, 0.8 * c.edge_length);
    EXPECT_LT(median, 1.05 * c.edge_length);
    EXPECT_GT(lengths[lengths.size() / 20], 0.4 * c.edge_length);      // 5th percentile
    EXPECT_LT(lengths[lengths.size() * 19 / 20], 1.5 * c.edge_length); // 95th
    const double estimate = double(remeshed_faces_estimate(c.mesh, c.edge_length));
    EXPECT_LE(double(result.num_faces()), estimate);
    EXPECT_GE(double(result.num_faces()), 0.7 * estimate);
  }
}

TEST(Remesh, VerticesLieOnTheInputSurface) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const PolygonMesh result = remesh(c.mesh, {.edge_length = c.edge_length});
    std::vector<Vec3> projected = result.positions;
    ClosestPoints(c.mesh).project(projected);
    double farthest = 0;
    for (size_t v = 0; v < projected.size(); ++v)
      farthest = std::max(farthest, norm(projected[v] - result.positions[v]));
    EXPECT_LT(farthest, 1e-4);
  }
}

TEST(Remesh, SameInputSameMesh) {
  const PolygonMesh mesh = genus_surface(2, 3000);
  const PolygonMesh a = remesh(mesh, {.edge_length = 0.12}), b = remesh(mesh, {.edge_length = 0.12});
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.face_vertices, b.face_vertices);
}

TEST(Remesh, RefusesBadLengthsAndTooManyFacesBeforeAnyWork) {
  const PolygonMesh mesh = sphere(500);
  EXPECT_THROW(remesh(mesh, {.edge_length = 0}), ParameterError);
  EXPECT_THROW(remesh(mesh, {.edge_length = -1}), ParameterError);
  EXPECT_THROW(remesh(mesh, {.edge_length = NAN}), ParameterError);
  const int64_t faces = remeshed_faces_estimate(mesh, 0.001);
  EXPECT_GT(faces, 10'000'000); // about 1.4 * 4 pi / (sqrt(3) / 4 * 1e-6)
  try {
    remesh(mesh, {.edge_length = 0.001, .max_faces = 1'000'000});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(faces)), std::string::npos) << e.what();
  }
}

// CGAL collapses no edge whose collapse would change the topology: a torus remeshed at
// lengths up to twice its size is still a torus (remesh's own check is a safety net).
TEST(Remesh, EvenACoarseLengthKeepsTheTopology) {
  const PolygonMesh mesh = torus(2000); // 2.7 wide, its tube 0.7
  for (double length : {0.8, 1.5, 3.0, 5.0}) {
    const PolygonMesh result = remesh(mesh, {.edge_length = length});
    EXPECT_EQ(topology_of(result), topology_of(mesh)) << length;
    EXPECT_GT(result.num_faces(), 0);
  }
}

TEST(ClosestPoints, MovesPointsToTheClosestPoint) {
  const PolygonMesh square = grid(200); // the unit square in z = 0
  std::vector<Vec3> points = {{0.25f, 0.5f, 0.3f}, {0.7f, 0.1f, -2}, {1.5f, 0.5f, 0}, {-1, -1, 1}};
  ClosestPoints(square).project(points);
  EXPECT_NEAR(points[0].x, 0.25, 1e-6);
  EXPECT_NEAR(points[0].y, 0.5, 1e-6);
  EXPECT_NEAR(points[0].z, 0, 1e-6);
  EXPECT_NEAR(points[1].z, 0, 1e-6);
  EXPECT_NEAR(points[2].x, 1, 1e-6); // beyond the edge: onto the edge
  EXPECT_NEAR(points[3].x, 0, 1e-6);
  EXPECT_NEAR(points[3].y, 0, 1e-6);
}

} // namespace
} // namespace meander
