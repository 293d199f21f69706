#include "meander/curve.h"

#include "meander/error.h"

#include <algorithm>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <string>

namespace meander {

namespace {

// The paper's weighted centre: the triangle read as a quad whose apex is doubled.
Vec3 control_point(Vec3 p, Vec3 apex, Vec3 n) { return (apex * 2.0f + p + n) * 0.25f; }

// The control point of the triangle named `id` (hamiltonian.h).
Vec3 triangle_control_point(const QuadMesh& quads, int32_t id) {
  const auto [p, apex, n] = cycle_triangle(quads, id);
  return control_point(quads.positions[size_t(p)], quads.positions[size_t(apex)], quads.positions[size_t(n)]);
}

} // namespace

Polylines control_polygons(const QuadMesh& quads, const TriangleCycle& cycle) {
  Polylines out;
  out.points.reserve(cycle.order.size());
  for (int32_t id : cycle.order) out.points.push_back(triangle_control_point(quads, id));
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

int points_per_segment(int64_t control_points, const CurveOptions& options) {
  if (options.samples < 1) throw ParameterError("samples", " must be at least 1 (got " + std::to_string(options.samples) + ")");
  const int k = options.smoothing == Smoothing::none ? 1 : options.samples;
  if (double(control_points) * k > 2147483647.0)
    throw ParameterError("samples", " " + std::to_string(k) + " would make more than 2^31 curve points");
  return k;
}

namespace {

// Where each curve starts among the sampled points: k points per control point.
std::vector<int32_t> sampled_start(const std::vector<int32_t>& control_start, int k) {
  std::vector<int32_t> start(control_start.size());
  for (size_t i = 0; i < start.size(); ++i) start[i] = control_start[i] * k;
  return start;
}

// Points [begin, end) of one closed curve of n control points, control point i being
// point(i), k points per segment. A point depends only on its segment's four control
// points, so any range can be sampled on its own and gives the same floats: blocks of a
// curve are sampled in parallel, and a streaming writer samples whatever block it writes.
// This loop makes most of the points a 10M-triangle mesh writes (120M at 4 samples), so
// the B-spline weights of the k sample positions are computed once, the smoothing is
// chosen once per segment, and the control indices wrap by a comparison (a division per
// control point showed in profiles).
template <typename Point>
void sample_range(const Point& point, int32_t n, int k, Smoothing smoothing, int64_t begin, int64_t end, Vec3* dst) {
  if (begin >= end) return;
  std::vector<std::array<float, 4>> weights;
  if (smoothing == Smoothing::bspline)
    for (int j = 0; j < k; ++j) weights.push_back(bspline_weights(float(j) / float(k)));
  const int64_t segment = begin / k;
  int j = int(begin % k);
  Vec3 p0 = point(int32_t((segment + n - 1) % n)), p1 = point(int32_t(segment % n)),
       p2 = point(int32_t((segment + 1) % n)), p3 = point(int32_t((segment + 2) % n));
  int32_t next = int32_t((segment + 3) % n);
  for (int64_t q = begin;;) {
    const int64_t stop = std::min<int64_t>(end, q + (k - j));
    if (smoothing == Smoothing::none) {
      for (; q < stop; ++q) *dst++ = p1;
    } else if (smoothing == Smoothing::bspline) {
      for (; q < stop; ++q, ++j) {
        const auto [b0, b1, b2, b3] = weights[size_t(j)];
        *dst++ = p0 * b0 + p1 * b1 + p2 * b2 + p3 * b3;
      }
    } else {
      for (; q < stop; ++q, ++j) *dst++ = catmull_rom(p0, p1, p2, p3, float(j) / float(k));
    }
    if (q == end) return;
    j = 0;
    p0 = p1;
    p1 = p2;
    p2 = p3;
    p3 = point(next);
    if (++next == n) next = 0;
  }
}

// Points [begin, end) of closed curves whose control point i (counted over all curves)
// is point(i), curve j having the control points [start[j], start[j + 1]), k points a
// segment: each curve's part of the range sampled on its own.
template <typename Point>
void sample_curves(const Point& point, std::span<const int32_t> start, int k, Smoothing smoothing, int64_t begin,
                   int64_t end, Vec3* dst) {
  size_t c = size_t(std::upper_bound(start.begin(), start.end(), int32_t(begin / k)) - start.begin()) - 1;
  for (; begin < end; ++c) {
    const int32_t first = start[c], n = start[c + 1] - first;
    const int64_t stop = std::min<int64_t>(end, int64_t(start[c + 1]) * k);
    sample_range([&](int32_t i) { return point(first + i); }, n, k, smoothing, begin - int64_t(first) * k,
                 stop - int64_t(first) * k, dst);
    dst += stop - begin;
    begin = stop;
  }
}

// Samples closed curves whose control point i of curve k is point(start[k] + i), so
// that the control polygon need not exist in memory.
template <typename Point>
Polylines sample_closed(const std::vector<int32_t>& start, const CurveOptions& options, const Point& point) {
  const int k = points_per_segment(start.back(), options);
  Polylines out;
  out.points.resize(size_t(start.back()) * size_t(k));
  out.start = sampled_start(start, k);
  for (size_t c = 0; c + 1 < start.size(); ++c) {
    const int32_t first = start[c], n = start[c + 1] - first;
    Vec3* curve = out.points.data() + size_t(out.start[c]);
    const auto control = [&](int32_t i) { return point(first + i); };
    tbb::parallel_for(tbb::blocked_range<int32_t>(0, n, 1 << 14), [&](const tbb::blocked_range<int32_t>& block) {
      sample_range(control, n, k, options.smoothing, int64_t(block.begin()) * k, int64_t(block.end()) * k,
                   curve + size_t(block.begin()) * size_t(k));
    });
  }
  return out;
}

// Control point i of the cycles, counted over all cycles in order. The samplers ask for
// them in order, and each waits on a quad and then on three positions at random: so
// each asks the cache ahead for the quad of a point further on and the positions of one
// nearer, whose quad was asked for earlier.
// Only the order given is read: a writer beside the walk gives the part walked so far.
struct CycleControl {
  static constexpr int32_t quad_ahead = 16, positions_ahead = 8;
  const QuadMesh* quads;
  std::span<const int32_t> order;
  Vec3 operator()(int32_t i) const {
    if (size_t(i) + quad_ahead < order.size()) {
      __builtin_prefetch(&quads->quads[size_t(order[size_t(i) + quad_ahead] >> 2)]);
      for (const int32_t v : cycle_triangle(*quads, order[size_t(i) + positions_ahead]))
        __builtin_prefetch(&quads->positions[size_t(v)]);
    }
    return triangle_control_point(*quads, order[size_t(i)]);
  }
};

} // namespace

Polylines smooth_curves(const Polylines& control, const CurveOptions& options) {
  return sample_closed(control.start, options, [&](int32_t i) { return control.points[size_t(i)]; });
}

Polylines cycle_curves(const QuadMesh& quads, const TriangleCycle& cycle, const CurveOptions& options) {
  return sample_closed(cycle.cycle_start, options, CycleControl{&quads, cycle.order});
}

void sample_cycle_curves(const QuadMesh& quads, std::span<const int32_t> order, std::span<const int32_t> start,
                         const CurveOptions& options, int64_t begin, int64_t end, Vec3* dst) {
  const int k = options.smoothing == Smoothing::none ? 1 : options.samples;
  sample_curves(CycleControl{&quads, order}, start, k, options.smoothing, begin, end, dst);
}

} // namespace meander
