// relax_curves: the curve's passes evened out on the surface, never crossing, the
// curves still closed and one per component.
#include "meander/relax.h"

#include "meander/error.h"
#include "meander/evenness.h"
#include "meander/pipeline.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <map>
#include <numbers>
#include <vector>

namespace meander {
namespace {

double cross2(Vec3 o, Vec3 a, Vec3 b) { return double(a.x - o.x) * (b.y - o.y) - double(a.y - o.y) * (b.x - o.x); }

// Whether segments ab and cd of the z = 0 plane cross (touching counts).
bool segments_cross(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const double d1 = cross2(c, d, a), d2 = cross2(c, d, b), d3 = cross2(a, b, c), d4 = cross2(a, b, d);
  return ((d1 >= 0 && d2 <= 0) || (d1 <= 0 && d2 >= 0)) && ((d3 >= 0 && d4 <= 0) || (d3 <= 0 && d4 >= 0));
}

// Pairs of segments of a closed plane curve that cross, segments sharing a point left
// out. A uniform grid of cells as wide as the longest segment: O(n) for an even curve.
int crossings(std::span<const Vec3> c) {
  const size_t n = c.size();
  double longest = 0;
  for (size_t i = 0; i < n; ++i) longest = std::max(longest, norm(c[(i + 1) % n] - c[i]));
  std::map<std::pair<int, int>, std::vector<size_t>> cells;
  auto cell = [&](Vec3 p) { return std::pair(int(std::floor(p.x / longest)), int(std::floor(p.y / longest))); };
  for (size_t i = 0; i < n; ++i) cells[cell(c[i])].push_back(i);
  int count = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto [x, y] = cell(c[i]);
    for (int dx = -2; dx <= 2; ++dx)
      for (int dy = -2; dy <= 2; ++dy) {
        const auto found = cells.find({x + dx, y + dy});
        if (found == cells.end()) continue;
        for (const size_t j : found->second) {
          if (j <= i || j == (i + 1) % n || i == (j + 1) % n) continue;
          count += segments_cross(c[i], c[(i + 1) % n], c[j], c[(j + 1) % n]);
        }
      }
  }
  return count;
}

// The curve on the unit square, made on its even remesh and moved onto it, before relaxing.
Polylines unrelaxed_curve(const PolygonMesh& mesh, double spacing) {
  const PolygonMesh even = remesh_to_spacing(mesh, spacing, Quadrangulation::dual_simplest);
  return make_curve(even, CurveJob{}).curves;
}

TEST(Relax, EvensTheGapsOfAPlaneCurveWithoutCrossingIt) {
  const PolygonMesh square = grid(2000);
  const double spacing = 0.03;
  const Polylines before = unrelaxed_curve(square, spacing);
  ASSERT_EQ(crossings(before.points), 0);
  const RelaxedCurves relaxed = relax_curves(before, square, ClosestPoints(square), {.spacing = spacing});
  const Polylines& after = relaxed.curves;
  ASSERT_EQ(after.size(), 1);
  EXPECT_EQ(crossings(after.points), 0);
  for (const Vec3 p : after.points) {
    EXPECT_EQ(p.z, 0);
    EXPECT_TRUE(p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1) << p.x << " " << p.y;
  }
  ASSERT_EQ(relaxed.normals.size(), after.points.size());
  for (const Vec3 n : relaxed.normals) EXPECT_NEAR(std::abs(n.z), 1, 1e-6);
  const EvennessReport was = measure_evenness(square, before), is = measure_evenness(square, after);
  EXPECT_GT(was.gap_cv, 0.15);
  EXPECT_LT(is.gap_cv, 0.12);
  EXPECT_NEAR(is.gap_median, spacing, 0.1 * spacing);
  EXPECT_GT(is.gap_p5, 0.75 * spacing);
  EXPECT_LT(is.coverage_max, was.coverage_max);
}

// The nearest pair of points of a closed curve that are other passes of each other
// (farther apart along it than 1.4 times their distance), by brute force.
double nearest_other_pass(std::span<const Vec3> c) {
  const size_t n = c.size();
  std::vector<double> along(n + 1, 0);
  for (size_t i = 0; i < n; ++i) along[i + 1] = along[i] + norm(c[(i + 1) % n] - c[i]);
  double nearest = INFINITY;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const double d = norm(c[j] - c[i]), a = std::min(along[j] - along[i], along[n] - (along[j] - along[i]));
      if (a > 1.4 * d) nearest = std::min(nearest, d);
    }
  return nearest;
}

// A needle (a hairpin pinched to a hundredth of a spacing, as grows where the curve
// moved onto the input jumps across a thin part) is cut off where its arms meet,
// within a single round, which could only push its arms a quarter of their distance
// apart.
TEST(Relax, CutsOffANeedle) {
  const PolygonMesh square = grid(2000);
  const double spacing = 0.1;
  // A circle with a needle half a spacing long sticking out of it.
  Polylines needle;
  for (int k = 0; k < 76; ++k) {
    const double angle = 2 * std::numbers::pi * k / 76;
    needle.points.push_back({float(0.5 + 0.3 * std::cos(angle)), float(0.5 + 0.3 * std::sin(angle)), 0});
    if (k == 0) {
      needle.points.push_back({0.85f, 0.5002f, 0});
      needle.points.push_back({0.8f, 0.5004f, 0});
    }
  }
  needle.start.push_back(int32_t(needle.points.size()));
  ASSERT_LT(nearest_other_pass(needle.points), 0.01 * spacing);
  ASSERT_EQ(crossings(needle.points), 0);
  const Polylines after = relax_curves(needle, square, ClosestPoints(square), {.spacing = spacing, .iterations = 1}).curves;
  ASSERT_EQ(after.size(), 1);
  EXPECT_GT(nearest_other_pass(after.points), 0.2 * spacing);
  EXPECT_EQ(crossings(after.points), 0);
}

// A curve that crosses itself (as the closest point folds a curve made on an even mesh
// that strays from the input by more than the gap between passes) is undone within a
// round, which by its moves alone would keep the crossing: still one closed curve.
TEST(Relax, UndoesACrossing) {
  const PolygonMesh square = grid(2000);
  const double spacing = 0.1;
  // A figure eight, crossing at its middle: there neither pass may move.
  Polylines eight;
  for (int k = 0; k < 120; ++k) {
    const double angle = 2 * std::numbers::pi * (k + 0.5) / 120;
    eight.points.push_back({float(0.5 + 0.35 * std::cos(angle)), float(0.5 + 0.35 * std::sin(angle) * std::cos(angle)), 0});
  }
  eight.start.push_back(120);
  ASSERT_EQ(crossings(eight.points), 1);
  const Polylines after = relax_curves(eight, square, ClosestPoints(square), {.spacing = spacing, .iterations = 1}).curves;
  ASSERT_EQ(after.size(), 1);
  EXPECT_EQ(crossings(after.points), 0);
}

// A curve whose points the closest point put on the two sides of a part thinner than
// the spacing (here a circle on a thin disk, half on top and half below) goes round the
// part's edge between them, not straight through it.
TEST(Relax, GoesRoundTheEdgeOfAThinPartNotThroughIt) {
  PolygonMesh disk = sphere(20000);
  for (Vec3& p : disk.positions) p.z *= 0.1f;
  const double spacing = 0.05;
  Polylines circle;
  for (int k = 0; k < 120; ++k) {
    const double angle = 2 * std::numbers::pi * k / 120;
    circle.points.push_back({float(0.95 * std::cos(angle)), float(0.95 * std::sin(angle)), k < 60 ? 0.1f : -0.1f});
  }
  circle.start.push_back(120);
  const ClosestPoints surface(disk);
  const Polylines on = relax_curves(circle, disk, surface, {.spacing = spacing, .iterations = 0}).curves;
  ASSERT_EQ(on.size(), 1);
  double longest = 0, outermost = 0;
  for (size_t i = 0; i < on.points.size(); ++i) {
    longest = std::max(longest, norm(on.points[(i + 1) % on.points.size()] - on.points[i]));
    outermost = std::max(outermost, norm(Vec3{on.points[i].x, on.points[i].y, 0}));
  }
  EXPECT_LT(longest, 0.5 * spacing);
  EXPECT_GT(outermost, 0.98);
}

TEST(Relax, KeepsEachCurveClosedAndOnItsComponent) {
  const PolygonMesh two = test::side_by_side(sphere(2000), torus(2000), {3, 0, 0});
  const double spacing = 0.1;
  const Polylines before = unrelaxed_curve(two, spacing);
  ASSERT_EQ(before.size(), 2);
  const Polylines after = relax_curves(before, two, ClosestPoints(two), {.spacing = spacing}).curves;
  ASSERT_EQ(after.size(), 2);
  // The sphere's curve stays on the sphere (x < 1.5), the torus's on the torus.
  for (int32_t k = 0; k < 2; ++k)
    for (const Vec3 p : after.polyline(k)) EXPECT_EQ(p.x < 1.5, before.polyline(k)[0].x < 1.5);
  EXPECT_EQ(after.open, std::vector<uint8_t>{});
}

// A component much smaller than the spacing (a fin that repair cut off) keeps a curve of
// at least 3 points: resampling at the spacing would leave too few to close.
TEST(Relax, ACurveSmallerThanTheSpacingStaysACurve) {
  const PolygonMesh two = test::side_by_side(sphere(500), scaled_to_size(sphere(200), 0.002), {3, 0, 0});
  const double spacing = 0.25;
  const Polylines before = make_curve(two, CurveJob{}).curves;
  ASSERT_EQ(before.size(), 2);
  const Polylines after = relax_curves(before, two, ClosestPoints(two), {.spacing = spacing}).curves;
  ASSERT_EQ(after.size(), 2);
  for (int32_t k = 0; k < 2; ++k) EXPECT_GE(after.polyline(k).size(), 3u) << k;
  EXPECT_NO_THROW(measure_evenness(two, after, {.surface_samples = 1000}));
}

TEST(Relax, TheSameWhateverTheNumberOfThreads) {
  const PolygonMesh mesh = torus(3000);
  const Polylines before = unrelaxed_curve(mesh, 0.08);
  const ClosestPoints surface(mesh);
  const RelaxedCurves many = relax_curves(before, mesh, surface, {.spacing = 0.08});
  const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const RelaxedCurves single = relax_curves(before, mesh, surface, {.spacing = 0.08});
  EXPECT_EQ(many.curves.points, single.curves.points);
  EXPECT_EQ(many.curves.start, single.curves.start);
  EXPECT_EQ(many.normals, single.normals);
}

TEST(Relax, RefusesWhatItCannotDo) {
  const PolygonMesh mesh = sphere(500);
  const ClosestPoints surface(mesh);
  const Polylines curve = unrelaxed_curve(mesh, 0.2);
  for (const double spacing : {0.0, -1.0, double(NAN), double(INFINITY)})
    EXPECT_THROW(relax_curves(curve, mesh, surface, {.spacing = spacing}), ParameterError) << spacing;
  EXPECT_THROW(relax_curves(curve, mesh, surface, {.spacing = 0.2, .iterations = -1}), ParameterError);
  Polylines open = curve;
  open.open = {1};
  EXPECT_THROW(relax_curves(open, mesh, surface, {.spacing = 0.2}), InputError);
}

} // namespace
} // namespace meander
