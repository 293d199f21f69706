#include "meander/check.h"
#include "meander/coarsen.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/remesh.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
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

// Triangle meshes of more than 8 times the faces of the result are coarsened first
// (coarsen.h): the result is the same kind of even mesh on the same surface. (A Möbius
// band's boundary and seam, which CGAL keeps, stay at the coarsened mesh's edges, about
// half the target.)
TEST(Remesh, AFineInputIsCoarsenedFirstToTheSameKindOfResult) {
  const std::vector<Case> fine = {{"sphere", sphere(100'000), 0.12},
                                  {"torus", torus(60'000), 0.1},
                                  {"grid", grid(40'000), 0.05}};
  for (const Case& c : fine) {
    SCOPED_TRACE(c.name);
    ASSERT_GT(c.mesh.num_faces(), 8 * remeshed_faces_estimate(c.mesh, c.edge_length));
    const PolygonMesh result = remesh(c.mesh, {.edge_length = c.edge_length});
    EXPECT_EQ(topology_of(result), topology_of(c.mesh));
    const std::vector<double> lengths = edge_lengths(result);
    EXPECT_GT(lengths[lengths.size() / 2], 0.8 * c.edge_length);
    EXPECT_LT(lengths[lengths.size() / 2], 1.05 * c.edge_length);
    std::vector<Vec3> projected = result.positions;
    ClosestPoints(c.mesh).project(projected);
    for (size_t v = 0; v < projected.size(); ++v) ASSERT_LT(norm(projected[v] - result.positions[v]), 1e-4);
  }
}

// A face whose corners lie on a line (CGAL's degtri_four.off: a square of four triangles
// with one such on its boundary) crashed CGAL 5.5's remeshing at fine lengths, once split
// into faces that were all a vertex had.
TEST(Remesh, AFaceWithItsCornersInALineIsTakenAway) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 1, 0}};
  for (const std::array<int32_t, 3> f : {std::array{0, 1, 2}, {0, 2, 3}, {2, 1, 4}, {3, 2, 4}}) mesh.add_face(f);
  ASSERT_EQ(inspect(mesh).zero_area_faces, 1);
  for (double length : {0.5, 0.1, 0.03}) {
    const PolygonMesh result = remesh(mesh, {.edge_length = length});
    EXPECT_EQ(topology_of(result), topology_of(mesh)) << length;
    EXPECT_EQ(inspect(result).zero_area_faces, 0) << length;
  }
}

TEST(Remesh, SameInputSameMesh) {
  const PolygonMesh mesh = genus_surface(2, 3000);
  const PolygonMesh a = remesh(mesh, {.edge_length = 0.12}), b = remesh(mesh, {.edge_length = 0.12});
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.face_vertices, b.face_vertices);
}

// CGAL's triangulate_faces cut a polygon of more than four corners by a Delaunay
// triangulation whose flips ran in the order of its faces' addresses: a Möbius band's
// seam (its edges split into several) and regular pentagons came out one way or another
// as the heap stood, and the curve with them. remesh() cuts such polygons itself.
TEST(Remesh, SameMeshWhateverTheHeapHolds) {
  MEANDER_REQUIRE_SHARED_MESHES();
  for (const auto& [file, length] : {std::pair{"moebius.obj", 0.28}, {"platonic_shelf.obj", 0.15}}) {
    SCOPED_TRACE(file);
    const PolygonMesh mesh = repair(read_mesh(test::shared_meshes() / file), file).mesh;
    const PolygonMesh first = remesh(mesh, {.edge_length = length});
    for (int held : {1000, 5000}) {
      std::vector<std::unique_ptr<char[]>> heap;
      for (int i = 0; i < held; ++i) heap.emplace_back(new char[size_t(16 + i * 37 % 300)]);
      const PolygonMesh again = remesh(mesh, {.edge_length = length});
      EXPECT_TRUE(again.positions == first.positions) << held;
      EXPECT_TRUE(again.face_vertices == first.face_vertices) << held;
    }
    EXPECT_EQ(inspect(first).zero_area_faces, 0);
  }
}

// Polygons are cut into triangles before CGAL sees them: a concave one (an L) and one
// whose corners lie on a circle, each a disc, come out as even discs of triangles, none
// flat, on the polygon's plane.
TEST(Remesh, CutsConcaveAndCocircularPolygons) {
  PolygonMesh l_shape;
  l_shape.positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  l_shape.add_face(std::array{0, 1, 2, 3, 4, 5});
  PolygonMesh circle;
  for (int i = 0; i < 12; ++i)
    circle.positions.push_back({float(std::cos(i * M_PI / 6)), float(std::sin(i * M_PI / 6)), 0.5f});
  std::vector<int32_t> all(12);
  for (int i = 0; i < 12; ++i) all[size_t(i)] = i;
  circle.add_face(all);
  for (const PolygonMesh* mesh : {&l_shape, &circle}) {
    for (double length : {0.6, 0.1}) {
      const PolygonMesh result = remesh(*mesh, {.edge_length = length});
      EXPECT_EQ(topology_of(result), topology_of(*mesh)) << length;
      EXPECT_EQ(inspect(result).faces_by_size.at(3), result.num_faces()) << length;
      EXPECT_EQ(inspect(result).zero_area_faces, 0) << length;
      EXPECT_NEAR(surface_area(result), surface_area(*mesh), 1e-3 * surface_area(*mesh)) << length;
      for (const Vec3 p : result.positions) EXPECT_EQ(p.z, mesh->positions[0].z);
    }
  }
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

// The distance from p to the nearest point of triangle t by brute force: its plane if the
// foot lies inside, else the nearest of its edges.
double distance_to_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
  auto segment = [&](Vec3d u, Vec3d v) {
    const double t = std::clamp(dot(p - u, v - u) / dot(v - u, v - u), 0.0, 1.0);
    return norm(p - (u + (v - u) * t));
  };
  const Vec3d n = cross(b - a, c - a);
  const Vec3d foot = p - n * (dot(p - a, n) / dot(n, n));
  const bool inside = dot(cross(b - a, foot - a), n) >= 0 && dot(cross(c - b, foot - b), n) >= 0 &&
                      dot(cross(a - c, foot - c), n) >= 0;
  return inside ? norm(p - foot) : std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// Embree's tree answers what a search of every triangle answers, with a hint or without,
// and of triangles equally near the lowest numbered.
TEST(ClosestPoints, FindsWhatEveryTriangleSearchedFinds) {
  const PolygonMesh mesh = torus(800);
  const ClosestPoints surface(mesh);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-2, 2);
  for (int k = 0; k < 300; ++k) {
    const Vec3d p{coordinate(random), coordinate(random), coordinate(random) / 2};
    double best = INFINITY;
    for (int32_t f = 0; f < mesh.num_faces(); ++f) {
      const std::span<const int32_t> t = mesh.face(f);
      best = std::min(best, distance_to_triangle(p, to_double(mesh.positions[size_t(t[0])]),
                                                 to_double(mesh.positions[size_t(t[1])]),
                                                 to_double(mesh.positions[size_t(t[2])])));
    }
    const ClosestPoints::Hit hit = surface.closest_hit(p);
    EXPECT_NEAR(norm(hit.point - p), best, 1e-9) << k;
    const std::span<const int32_t> t = mesh.face(hit.triangle);
    const Vec3d a = to_double(mesh.positions[size_t(t[0])]), n = cross(to_double(mesh.positions[size_t(t[1])]) - a,
                                                                          to_double(mesh.positions[size_t(t[2])]) - a);
    EXPECT_NEAR(dot(hit.normal, n) / norm(n), 1, 1e-9);
    const ClosestPoints::Hit hinted = surface.closest_hit(p, surface.closest_hit(p + Vec3d{0.1, 0, 0}));
    EXPECT_EQ(hinted.point, hit.point);
    EXPECT_EQ(hinted.triangle, hit.triangle);
  }
  // Above a vertex of the square, every triangle around it is as near: the lowest wins.
  const PolygonMesh square = grid(200);
  const Vec3 corner = square.positions[size_t(square.face(57)[0])];
  int32_t lowest = square.num_faces();
  for (int32_t f = 0; f < square.num_faces(); ++f)
    for (int32_t v : square.face(f))
      if (square.positions[size_t(v)] == corner) lowest = std::min(lowest, f);
  EXPECT_EQ(ClosestPoints(square).closest_hit(to_double(corner) + Vec3d{0, 0, 1}).triangle, lowest);
}

// any_near is handed every triangle within the distance, each with its point nearest p
// (as a search of every triangle finds them), and no other; it stops at one that holds.
TEST(ClosestPoints, AnyNearIsHandedTheTrianglesWithinTheDistance) {
  const PolygonMesh mesh = torus(800);
  const ClosestPoints surface(mesh);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-2, 2);
  for (int k = 0; k < 100; ++k) {
    const Vec3d p{coordinate(random), coordinate(random), coordinate(random) / 2};
    const double within = 0.3;
    std::vector<double> expected; // the distances of the triangles within, sorted
    for (int32_t f = 0; f < mesh.num_faces(); ++f) {
      const std::span<const int32_t> t = mesh.face(f);
      const double d = distance_to_triangle(p, to_double(mesh.positions[size_t(t[0])]), to_double(mesh.positions[size_t(t[1])]),
                                            to_double(mesh.positions[size_t(t[2])]));
      if (d <= within) expected.push_back(d);
    }
    std::sort(expected.begin(), expected.end());
    std::vector<double> seen;
    EXPECT_FALSE(surface.any_near(p, within, [&](Vec3d closest, const std::array<Vec3d, 3>& corners) {
      EXPECT_NEAR(norm(closest - p), distance_to_triangle(p, corners[0], corners[1], corners[2]), 1e-9);
      seen.push_back(norm(closest - p));
      return false;
    }));
    std::sort(seen.begin(), seen.end());
    ASSERT_EQ(seen.size(), expected.size()) << k;
    for (size_t i = 0; i < seen.size(); ++i) EXPECT_NEAR(seen[i], expected[i], 1e-9);
    int tried = 0;
    EXPECT_EQ(surface.any_near(p, within, [&](Vec3d, const std::array<Vec3d, 3>&) { return ++tried == 1; }), !expected.empty());
    EXPECT_EQ(tried, expected.empty() ? 0 : 1);
  }
}

// A point moved a little from a hit, outside a convex surface, walks to the closest
// point, as the tree finds it, also when it moved past corners of faces or far across a
// fine surface (then the tree takes over); and it stays on the sheet it was on where
// another is nearer.
TEST(ClosestPoints, NearbyHitWalksToTheClosestPointAround) {
  const PolygonMesh ball = sphere(20000);
  const ClosestPoints surface(ball);
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  for (int k = 0; k < 300; ++k) {
    const ClosestPoints::Hit from = surface.closest_hit({gauss(random), gauss(random), gauss(random)});
    // Along the plane of its face, which lies outside the sphere.
    const Vec3d move = cross(from.normal, {gauss(random), gauss(random), gauss(random)});
    const Vec3d p = from.point + move * (k < 150 ? 0.02 : 0.3);
    const ClosestPoints::Hit walked = surface.nearby_hit(p, from), closest = surface.closest_hit(p);
    EXPECT_NEAR(norm(walked.point - closest.point), 0, 1e-9) << k;
  }
  const PolygonMesh square = grid(20000);
  const ClosestPoints plane(square);
  const ClosestPoints::Hit corner = plane.closest_hit({0, 0, 0});
  EXPECT_EQ(plane.nearby_hit({0.9, 0.8, 0.5}, corner).point, plane.closest_hit({0.9, 0.8, 0.5}).point);
  // Two sheets 0.1 apart: a point moved to 0.06 below the upper one stays on it.
  PolygonMesh sheets = square;
  for (Vec3 p : square.positions) sheets.positions.push_back({p.x, p.y, p.z - 0.1f});
  for (int32_t f = 0; f < square.num_faces(); ++f) {
    std::vector<int32_t> face(square.face(f).begin(), square.face(f).end());
    for (int32_t& v : face) v += square.num_vertices();
    sheets.add_face(face);
  }
  const ClosestPoints two(sheets);
  const ClosestPoints::Hit upper = two.closest_hit({0.5, 0.5, 0.01});
  ASSERT_NEAR(upper.point.z, 0, 1e-9);
  EXPECT_NEAR(two.closest_hit({0.52, 0.5, -0.06}).point.z, -0.1, 1e-6);
  EXPECT_NEAR(two.nearby_hit({0.52, 0.5, -0.06}, upper).point.z, 0, 1e-9);
}

// A path between points on the two sides of a thin disk goes round its rim, every point
// on the surface and about a step from the last; across a large face it goes about
// straight; none is found where every way is longer than allowed.
TEST(ClosestPoints, PathGoesRoundTheEdgeOfAThinPart) {
  PolygonMesh disk = sphere(20000);
  for (Vec3& p : disk.positions) p.z *= 0.05f;
  const ClosestPoints surface(disk);
  const ClosestPoints::Hit top = surface.closest_hit({0.9, 0, 0.1}), bottom = surface.closest_hit({0.9, 0, -0.1});
  ASSERT_GT(top.point.z, 0);
  ASSERT_LT(bottom.point.z, 0);
  const double step = 0.02;
  const std::vector<ClosestPoints::Hit> way = surface.path(top, bottom, step, 1);
  ASSERT_FALSE(way.empty());
  double outermost = 0, longest = 0;
  const ClosestPoints::Hit* last = &top;
  for (const ClosestPoints::Hit& h : way) {
    EXPECT_NEAR(norm(surface.closest(h.point) - h.point), 0, 1e-9);
    outermost = std::max(outermost, h.point.x);
    longest = std::max(longest, norm(h.point - last->point));
    last = &h;
  }
  longest = std::max(longest, norm(bottom.point - last->point));
  EXPECT_GT(outermost, 0.98); // round the rim, at x = 1
  EXPECT_LT(longest, 1.5 * step);
  EXPECT_TRUE(surface.path(top, bottom, step, 0.1).empty()); // the way is about 0.2 long
  // Across the two triangles of a square, near the straight line.
  const PolygonMesh square = grid(2);
  const ClosestPoints plane(square);
  const ClosestPoints::Hit from = plane.closest_hit({0.1, 0.8, 0}), to = plane.closest_hit({0.9, 0.3, 0});
  ASSERT_NE(from.triangle, to.triangle);
  const std::vector<ClosestPoints::Hit> straight = plane.path(from, to, 0.05, 2);
  ASSERT_EQ(straight.size(), 18u); // 0.94 long
  for (const ClosestPoints::Hit& h : straight) {
    const Vec3d along = to.point - from.point;
    EXPECT_LT(norm(cross(h.point - from.point, along)) / norm(along), 0.05);
  }
}

// Each polygon fanned from its first vertex, as the writers triangulate it.
PolygonMesh fanned(const PolygonMesh& mesh) {
  PolygonMesh out;
  out.positions = mesh.positions;
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    for (size_t i = 1; i + 1 < mesh.face(f).size(); ++i) out.add_face({mesh.face(f)[0], mesh.face(f)[i], mesh.face(f)[i + 1]});
  return out;
}

// Fine inputs of every kind remesh() coarsens: a UV sphere (whose poles' long thin fans
// meshoptimizer's simplifier folded), closed surfaces of genus 1 to 3, a disk, a Möbius
// band and two components at once.
std::vector<Case> fine_cases() {
  return {{"sphere", sphere(100'000), 0.1},
          {"torus", torus(60'000), 0.1},
          {"pretzel", fanned(genus_surface(2, 30'000)), 0.25},
          {"genus 3", fanned(genus_surface(3, 40'000)), 0.25},
          {"grid", grid(40'000), 0.04},
          {"moebius", fanned(moebius(30'000)), 0.06},
          {"sphere and torus", test::side_by_side(sphere(20'000), torus(20'000), {3, 0, 0}), 0.15}};
}

TEST(Coarsen, KeepsTheTopologyAndCollapsesTheShortEdges) {
  for (const Case& c : fine_cases()) {
    SCOPED_TRACE(c.name);
    const PolygonMesh result = coarsen(c.mesh, c.edge_length);
    EXPECT_EQ(topology_of(result), topology_of(c.mesh));
    const MeshReport report = inspect(result);
    EXPECT_EQ(report.non_manifold_edges + report.non_manifold_vertices + report.degenerate_faces + report.duplicate_faces +
                  report.zero_area_faces,
              0);
    EXPECT_LT(result.num_faces(), c.mesh.num_faces() / 10);
    const std::vector<double> lengths = edge_lengths(result);
    EXPECT_GT(lengths[lengths.size() / 2], 0.5 * c.edge_length); // the median
    EXPECT_LE(lengths.back(), 1.5 * c.edge_length);              // the input's are all shorter
  }
}

TEST(Coarsen, EveryVertexIsOneOfTheInputsInItsOrder) {
  for (const Case& c : fine_cases()) {
    SCOPED_TRACE(c.name);
    const PolygonMesh result = coarsen(c.mesh, c.edge_length);
    size_t next = 0; // the input vertex after the last one matched
    for (const Vec3 p : result.positions) {
      while (next < c.mesh.positions.size() && !(c.mesh.positions[next] == p)) ++next;
      ASSERT_LT(next, c.mesh.positions.size()) << "a vertex that is not the input's, or out of order";
      ++next;
    }
  }
}

TEST(Coarsen, SameInputSameMesh) {
  const PolygonMesh mesh = fanned(genus_surface(2, 30'000));
  const PolygonMesh a = coarsen(mesh, 0.1), b = coarsen(mesh, 0.1);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.face_vertices, b.face_vertices);
}

// The smallest closed surface and the smallest disk, and a triangular bipyramid whose
// short ring edge would pinch it (its ends share the ring's third vertex, which the link
// condition sees; no face turns by more than 12 degrees): any collapse would fold them
// flat, close the boundary or pinch, so none is made however long the length.
TEST(Coarsen, LeavesWhatCannotBeCollapsed) {
  PolygonMesh tetrahedron;
  tetrahedron.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const std::array<int32_t, 3> f : {std::array{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}) tetrahedron.add_face(f);
  PolygonMesh triangle;
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.add_face({0, 1, 2});
  PolygonMesh bipyramid;
  bipyramid.positions = {{1, 0, 0}, {0.9f, 0.3f, 0}, {-0.5f, -0.87f, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const std::array<int32_t, 3> f : {std::array{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {1, 0, 4}, {2, 1, 4}, {0, 2, 4}})
    bipyramid.add_face(f);
  for (const PolygonMesh* mesh : {&tetrahedron, &triangle, &bipyramid}) {
    const PolygonMesh result = coarsen(*mesh, 10);
    EXPECT_EQ(result.positions, mesh->positions);
    EXPECT_EQ(result.face_vertices, mesh->face_vertices);
  }
}

TEST(Coarsen, RefusesPolygons) {
  PolygonMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.add_face({0, 1, 2, 3});
  EXPECT_THROW(coarsen(quad, 1), InputError);
}

} // namespace
} // namespace meander
