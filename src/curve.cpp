#include "meander/curve.h"

#include "meander/error.h"

#include <cmath>
#include <string>

namespace meander {

Polylines control_polygons(const QuadMesh& quads, const TriangleCycle& cycle) {
  Polylines out;
  out.points.reserve(cycle.order.size());
  for (int32_t id : cycle.order) {
    const auto [p, apex, n] = cycle_triangle(quads, id);
    const Vec3 a = quads.positions[size_t(apex)], b = quads.positions[size_t(p)], c = quads.positions[size_t(n)];
    out.points.push_back((a * 2.0f + b + c) * 0.25f);
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

namespace {

// Uniform cubic B-spline basis at u in [0,1), for the segment between p1 and p2.
Vec3 bspline(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, float u) {
  const float u2 = u * u, u3 = u2 * u;
  const float b0 = (1 - u) * (1 - u) * (1 - u) / 6;
  const float b1 = (3 * u3 - 6 * u2 + 4) / 6;
  const float b2 = (-3 * u3 + 3 * u2 + 3 * u + 1) / 6;
  const float b3 = u3 / 6;
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

Polylines smooth_curves(const Polylines& control, const CurveOptions& options) {
  if (options.samples < 1) throw UsageError("--samples must be at least 1 (got " + std::to_string(options.samples) + ")");
  if (options.smoothing == Smoothing::none) return control;
  const int k = options.samples;
  if (double(control.points.size()) * k > 2147483647.0)
    throw UsageError("--samples " + std::to_string(k) + " would make more than 2^31 curve points");
  Polylines out;
  out.points.resize(control.points.size() * size_t(k));
  out.start.resize(control.start.size());
  for (size_t i = 0; i < control.start.size(); ++i) out.start[i] = control.start[i] * k;
  for (int32_t c = 0; c < control.size(); ++c) {
    const auto p = control.polyline(c);
    const int32_t n = int32_t(p.size());
    Vec3* dst = out.points.data() + size_t(out.start[size_t(c)]);
    for (int32_t i = 0; i < n; ++i) {
      const Vec3 p0 = p[size_t((i + n - 1) % n)], p1 = p[size_t(i)], p2 = p[size_t((i + 1) % n)],
                 p3 = p[size_t((i + 2) % n)];
      for (int j = 0; j < k; ++j) {
        const float u = float(j) / float(k);
        *dst++ = options.smoothing == Smoothing::bspline ? bspline(p0, p1, p2, p3, u) : catmull_rom(p0, p1, p2, p3, u);
      }
    }
  }
  return out;
}

} // namespace meander
