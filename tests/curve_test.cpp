#include "meander/curve.h"

#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

namespace meander {
namespace {

// The control point is the paper's weighted centre (2 p_apex + p + n) / 4.
TEST(Curve, ControlPointIsTheWeightedCentre) {
  QuadMesh q;
  q.positions = {{0, 0, 0}, {4, 0, 0}, {0, 8, 0}, {4, 8, 0}};
  q.quads = {{1, 0, 2, 3}};
  TriangleCycle c;
  c.order = {4 * 0 + 1, 4 * 0 + 2}; // apex corner 1 (vertex 0), then apex corner 2 (vertex 2)
  c.cycle_start = {0, 2};
  const Polylines p = control_polygons(q, c);
  ASSERT_EQ(p.points.size(), 2u);
  EXPECT_EQ(p.points[0], (Vec3{1, 2, 0})); // (2*(0,0,0) + (4,0,0) + (0,8,0)) / 4
  EXPECT_EQ(p.points[1], (Vec3{1, 6, 0})); // (2*(0,8,0) + (0,0,0) + (4,8,0)) / 4
}

Polylines square() {
  Polylines p;
  p.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  p.start = {0, 4};
  return p;
}

// A closed uniform B-spline of a square lies strictly inside it; sample 0 of
// each segment is (P_{i-1} + 4 P_i + P_{i+1}) / 6.
TEST(Curve, BsplineOfASquare) {
  const Polylines s = smooth_curves(square(), {.smoothing = Smoothing::bspline, .samples = 5});
  ASSERT_EQ(s.points.size(), 20u);
  EXPECT_NEAR(s.points[0].x, 1.0 / 6, 1e-6);
  EXPECT_NEAR(s.points[0].y, 1.0 / 6, 1e-6);
  for (Vec3 p : s.points) {
    EXPECT_GT(p.x, 0.0f);
    EXPECT_LT(p.x, 1.0f);
    EXPECT_GT(p.y, 0.0f);
    EXPECT_LT(p.y, 1.0f);
  }
}

// Catmull-Rom interpolates: sample 0 of each segment is the control point itself, even
// with repeated control points (zero-area faces) which must not produce NaN.
TEST(Curve, CatmullRomInterpolatesAndSurvivesRepeatedPoints) {
  Polylines p = square();
  p.points.insert(p.points.begin() + 2, p.points[1]);
  p.start = {0, 5};
  const Polylines s = smooth_curves(p, {.smoothing = Smoothing::catmull_rom, .samples = 4});
  for (int i = 0; i < 5; ++i) EXPECT_EQ(s.points[size_t(4 * i)], p.points[size_t(i)]);
  for (Vec3 q : s.points) EXPECT_TRUE(is_finite(q));
}

TEST(Curve, NoneKeepsTheControlPolygonAndBadSamplesAreRefused) {
  EXPECT_EQ(smooth_curves(square(), {.smoothing = Smoothing::none}).points, square().points);
  EXPECT_THROW(smooth_curves(square(), {.samples = 0}), UsageError);
  EXPECT_THROW(parse_smoothing("bezier"), UsageError);
}

// The curve stays on the surface: on a sphere every sample of the smoothed curve lies
// within a small fraction of the radius of the unit sphere (chords cut inside a little).
TEST(Curve, SmoothCurveStaysNearTheSphere) {
  const PolygonMesh mesh = sphere(2000);
  const QuadMesh quads = dual_simplest(mesh, build_connectivity(mesh));
  const TriangleCycle cycle = hamiltonian_cycle(quads);
  const Polylines curve = smooth_curves(control_polygons(quads, cycle), {.samples = 3});
  ASSERT_EQ(curve.size(), 1);
  for (Smoothing s : {Smoothing::bspline, Smoothing::catmull_rom, Smoothing::none}) {
    // The streaming path gives exactly the points of the two-step one.
    const CurveOptions options{.smoothing = s, .samples = 3};
    EXPECT_EQ(cycle_curves(quads, cycle, options).points, smooth_curves(control_polygons(quads, cycle), options).points);
  }
  for (Vec3 p : curve.points) {
    EXPECT_LT(norm(p), 1.0 + 1e-5);
    EXPECT_GT(norm(p), 0.97);
  }
}

} // namespace
} // namespace meander
