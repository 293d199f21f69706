#include "meander/curve.h"

#include "meander/error.h"

#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <string>

namespace meander {

namespace {

// The paper's weighted centre: the triangle read as a quad whose apex is doubled.
Vec3 control_point(Vec3 p, Vec3 apex, Vec3 n) { return (apex * 2.0f + p + n) * 0.25f; }

} // namespace

Polylines control_polygons(const QuadMesh& quads, const TriangleCycle& cycle) {
  Polylines out;
  out.points.reserve(cycle.order.size());
  for (int32_t id : cycle.order) {
    const auto [p, apex, n] = cycle_triangle(quads, id);
    out.points.push_back(control_point(quads.positions[size_t(p)], quads.positions[size_t(apex)], quads.positions[size_t(n)]));
  }
  out.start = cycle.cycle_start;
  return out;
}

Smoothing parse_smoothing(std::string_view name) {
  if (name == "bspline") return Smoothing::bspline;
  if (name == "catmull-rom") return Smoothing::catmull_rom;
  if (name == "none") return Smoothing::none;
  throw UsageError("unknown smoothing '" + std::string(name) + "' (expected bspline, catmull-rom or none)");
}

std::array<float, 4> bspline_weights(float u) {
  const float u2 = u * u, u3 = u2 * u;
  return {(1 - u) * (1 - u) * (1 - u) / 6, (3 * u3 - 6 * u2 + 4) / 6, (-3 * u3 + 3 * u2 + 3 * u + 1) / 6, u3 / 6};
}

namespace {

// Uniform cubic B-spline at u in [0,1), for the segment between p1 and p2.
Vec3 bspline(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, float u) {
  const auto [b0, b1, b2, b3] = bspline_weights(u);
  return p0 * b0 + p1 * b1 + p2 * b2 + p3 * b3;
}

// Centripetal Catmull-Rom (alpha = 1/2) between p1 and p2, by the Barry-Goldman
// pyramid. Knot gaps get a floor so repeated control points (zero-area faces) do not
// divide by zero; the segment then degenerates gracefully to a line.
Vec3 catmull_rom(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, float u) {
  auto gap = [](Vec3 a, Vec3 b) { return std::max(std::sqrt(float(norm(b - a))), 1e-6f); };
  const float t0 = 0, t1 = t0 + gap(p0, p1), t2 = t1 + gap(p1, p2), t3 = t2 + gap(p2, p3);
  const float t = t1 + u * (t2 - t1);
  auto lerp = [](Vec3 a, Vec3 b, float ta, float tb, float x) { return a * ((tb - x) / (tb - ta)) + b * ((x - ta) / (tb - ta)); };
  const Vec3 a1 = lerp(p0, p1, t0, t1, t), a2 = lerp(p1, p2, t1, t2, t), a3 = lerp(p2, p3, t2, t3, t);
  const Vec3 b1 = lerp(a1, a2, t0, t2, t), b2 = lerp(a2, a3, t1, t3, t);
  return lerp(b1, b2, t1, t2, t);
}

} // namespace

namespace {

// Samples closed curves whose control point i of curve k is point(start[k] + i), so
// that the control polygon need not exist in memory.
template <typename Point>
Polylines sample_closed(const std::vector<int32_t>& start, const CurveOptions& options, Point point) {
  if (options.samples < 1) throw UsageError("--samples must be at least 1 (got " + std::to_string(options.samples) + ")");
  const int k = options.smoothing == Smoothing::none ? 1 : options.samples;
  if (double(start.back()) * k > 2147483647.0)
    throw UsageError("--samples " + std::to_string(k) + " would make more than 2^31 curve points");
  Polylines out;
  out.points.resize(size_t(start.back()) * size_t(k));
  out.start.resize(start.size());
  for (size_t i = 0; i < start.size(); ++i) out.start[i] = start[i] * k;
  // Segments are independent given their four control points, so blocks of a curve are
  // sampled in parallel, each starting its own window.
  for (size_t c = 0; c + 1 < start.size(); ++c) {
    const int32_t first = start[c], n = start[c + 1] - first;
    Vec3* curve = out.points.data() + size_t(out.start[c]);
    tbb::parallel_for(tbb::blocked_range<int32_t>(0, n, 1 << 14), [&](const tbb::blocked_range<int32_t>& block) {
      auto at = [&](int32_t i) { return point(first + i % n); };
      Vec3 p0 = at(block.begin() + n - 1), p1 = at(block.begin()), p2 = at(block.begin() + 1), p3 = at(block.begin() + 2);
      Vec3* dst = curve + size_t(block.begin()) * size_t(k);
      for (int32_t i = block.begin(); i < block.end(); ++i) {
        if (options.smoothing == Smoothing::none) {
          *dst++ = p1;
        } else {
          for (int j = 0; j < k; ++j) {
            const float u = float(j) / float(k);
            *dst++ = options.smoothing == Smoothing::bspline ? bspline(p0, p1, p2, p3, u) : catmull_rom(p0, p1, p2, p3, u);
          }
        }
        p0 = p1;
        p1 = p2;
        p2 = p3;
        p3 = at(i + 3);
      }
    });
  }
  return out;
}

} // namespace

Polylines smooth_curves(const Polylines& control, const CurveOptions& options) {
  return sample_closed(control.start, options, [&](int32_t i) { return control.points[size_t(i)]; });
}

Polylines cycle_curves(const QuadMesh& quads, const TriangleCycle& cycle, const CurveOptions& options) {
  return sample_closed(cycle.cycle_start, options, [&](int32_t i) {
    const auto [p, apex, n] = cycle_triangle(quads, cycle.order[size_t(i)]);
    return control_point(quads.positions[size_t(p)], quads.positions[size_t(apex)], quads.positions[size_t(n)]);
  });
}

} // namespace meander
