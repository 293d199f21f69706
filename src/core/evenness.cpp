#include "meander/evenness.h"

#include "meander/error.h"
#include "point_grid.h"
#include "surface_samples.h"
#include "random.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meander {

namespace {

// Issue 34's test for another pass: farther along the curve than 1.4 times the straight
// distance. A straight stretch has ratio 1; across a hairpin the ratio grows without
// bound; on a circle the points beyond about 157 degrees count.
constexpr double kPassRatio = 1.4;

// How far, in spacing estimates, a nearest point is looked for. A grid query visits O(k^3)
// cells to find a point k cells away, so a surface far from every curve (curves of
// another mesh, or of only some of its components) would take hours; within this reach
// it takes at most milliseconds a query.
constexpr double kReach = 32;

// The automatic step gives at most this many points (about 1 GB of work arrays): a curve
// of a 10M-triangle mesh would get hundreds of millions at spacing_estimate / 8.
constexpr double kMaxAutomaticPoints = 1 << 24;

// How far outside the surface's bounding box, in diagonals, a curve may stray before it
// is taken for a curve of another mesh, whose spacing estimate would mean nothing.
constexpr double kBoxSlack = 0.1;

std::string curve_name(int32_t k) { return "curve " + std::to_string(k); }

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

void check_input(const PolygonMesh& surface, const Polylines& curves, const EvennessOptions& options) {
  if (!(options.step >= 0 && std::isfinite(options.step)))
    throw ParameterError("step", " must be 0 (automatic) or a positive number (got " + number(options.step) + ")");
  if (options.surface_samples < 1)
    throw ParameterError("surface_samples",
                         " must be at least 1 (got " + std::to_string(options.surface_samples) + ")");
  if (curves.size() < 1) throw InputError("no curves to measure");
  for (int32_t k = 0; k < curves.size(); ++k) {
    if (!curves.closed(k)) throw InputError(curve_name(k) + " is open: evenness is measured on closed curves");
    const auto c = curves.polyline(k);
    if (c.size() < 3)
      throw InputError(curve_name(k) + " has " + std::to_string(c.size()) + " point" + (c.size() == 1 ? "" : "s") +
                       ", fewer than the 3 of a closed curve");
    for (size_t j = 0; j < c.size(); ++j)
      if (!is_finite(c[j])) throw InputError(curve_name(k) + ": point " + std::to_string(j) + " is not finite");
  }
  for (int32_t v = 0; v < surface.num_vertices(); ++v)
    if (!is_finite(surface.positions[size_t(v)]))
      throw InputError("surface vertex " + std::to_string(v) + " has a non-finite position");
  const Box3 box = bounding_box(surface.positions);
  const double slack = kBoxSlack * box.diagonal();
  auto outside = [&](Vec3 p) {
    return p.x < box.min.x - slack || p.y < box.min.y - slack || p.z < box.min.z - slack || p.x > box.max.x + slack ||
           p.y > box.max.y + slack || p.z > box.max.z + slack;
  };
  for (int32_t k = 0; k < curves.size(); ++k) {
    const auto c = curves.polyline(k);
    for (size_t j = 0; j < c.size(); ++j)
      if (outside(c[j]))
        throw InputError(curve_name(k) + ": point " + std::to_string(j) +
                         " lies outside the surface's bounding box grown by a tenth of its diagonal: the curves "
                         "are not on this surface");
  }
}

// a + (b - a) t, in double, rounded once.
Vec3 lerp(Vec3 a, Vec3 b, double t) {
  return {float(a.x + (double(b.x) - a.x) * t), float(a.y + (double(b.y) - a.y) * t),
          float(a.z + (double(b.z) - a.z) * t)};
}

double closed_length(std::span<const Vec3> c) {
  double length = 0;
  for (size_t j = 0; j < c.size(); ++j) length += norm(c[(j + 1) % c.size()] - c[j]);
  return length;
}

// The curves resampled at equal arc-length steps: curve k gets count[k] points,
// spacing[k] apart along it, its point j at arc length j * spacing[k] from its first.
struct Resampled {
  std::vector<Vec3> points;
  std::vector<int32_t> curve; // of each point
  std::vector<int32_t> index; // of each point within its curve
  std::vector<int32_t> count;
  std::vector<double> spacing;
};

Resampled resample(const Polylines& curves, std::span<const double> length, double step) {
  double total = 0;
  for (double l : length) total += std::max(3.0, std::ceil(l / step));
  if (!(total < 2147483648.0))
    throw ParameterError("step", " " + number(step) + " would make 2^31 curve points or more");
  Resampled r;
  r.points.reserve(size_t(total));
  r.curve.reserve(size_t(total));
  r.index.reserve(size_t(total));
  for (int32_t k = 0; k < curves.size(); ++k) {
    const auto c = curves.polyline(k);
    // At least the 3 points of a closed curve, however short.
    const int32_t m = int32_t(std::max(3.0, std::ceil(length[size_t(k)] / step)));
    const double h = length[size_t(k)] / m;
    r.count.push_back(m);
    r.spacing.push_back(h);
    size_t segment = 0;
    double begin = 0, segment_length = norm(c[1] - c[0]);
    for (int32_t j = 0; j < m; ++j) {
      const double s = j * h;
      while (segment + 1 < c.size() && begin + segment_length <= s) {
        begin += segment_length;
        ++segment;
        segment_length = norm(c[(segment + 1) % c.size()] - c[segment]);
      }
      const double t = segment_length > 0 ? std::clamp((s - begin) / segment_length, 0.0, 1.0) : 0.0;
      r.points.push_back(lerp(c[segment], c[(segment + 1) % c.size()], t));
      r.curve.push_back(k);
      r.index.push_back(j);
    }
  }
  return r;
}

// The q-quantile of v, interpolated between ranks. Reorders v. O(n).
double percentile(std::vector<double>& v, double q) {
  const double at = q * double(v.size() - 1);
  const size_t i = size_t(at);
  std::nth_element(v.begin(), v.begin() + ptrdiff_t(i), v.end());
  if (i + 1 == v.size()) return v[i];
  const double above = *std::min_element(v.begin() + ptrdiff_t(i) + 1, v.end());
  return v[i] + (above - v[i]) * (at - double(i));
}

} // namespace

EvennessReport measure_evenness(const PolygonMesh& surface, const Polylines& curves, const EvennessOptions& options) {
  check_input(surface, curves, options);
  std::vector<double> length(size_t(curves.size()));
  double total_length = 0;
  for (int32_t k = 0; k < curves.size(); ++k) {
    length[size_t(k)] = closed_length(curves.polyline(k));
    if (!(length[size_t(k)] > 0)) throw InputError(curve_name(k) + " has zero length");
    total_length += length[size_t(k)];
  }
  const std::vector<double> cumulative = cumulative_areas(surface);
  if (cumulative.empty() || !(cumulative.back() > 0)) throw InputError("the surface has no area");

  EvennessReport report;
  report.spacing_estimate = cumulative.back() / total_length;
  report.step =
      options.step > 0 ? options.step : std::max(report.spacing_estimate / 8, total_length / kMaxAutomaticPoints);
  const Resampled r = resample(curves, length, report.step);
  report.points = int32_t(r.points.size());

  const std::vector<Vec3> samples = surface_samples(surface, cumulative, options.surface_samples, options.seed);
  Box3 box;
  for (Vec3 p : r.points) box.extend(p);
  for (Vec3 p : samples) box.extend(p);
  const PointGrid grid(r.points, report.spacing_estimate, box);
  const double reach = kReach * report.spacing_estimate;

  std::vector<double> gap(r.points.size());
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, report.points, 1024), [&](const tbb::blocked_range<int32_t>& range) {
    for (int32_t i = range.begin(); i < range.end(); ++i) {
      const int32_t k = r.curve[size_t(i)];
      const int32_t m = r.count[size_t(k)];
      const double limit = kPassRatio * kPassRatio / (r.spacing[size_t(k)] * r.spacing[size_t(k)]);
      gap[size_t(i)] = std::sqrt(grid.nearest_squared(r.points[size_t(i)], reach, [&](int32_t j, double d2) {
        if (r.curve[size_t(j)] != k) return true;
        const int32_t apart = std::abs(r.index[size_t(j)] - r.index[size_t(i)]);
        const double along = std::min(apart, m - apart);
        return along * along > limit * d2;
      }));
    }
  });
  std::erase_if(gap, [](double g) { return std::isinf(g); });
  report.unpaired = report.points - int32_t(gap.size());
  if (gap.empty()) throw InputError("no point of the curves has another pass to measure a gap to");
  double sum = 0;
  for (double g : gap) sum += g;
  report.gap_mean = sum / double(gap.size());
  double squares = 0;
  for (double g : gap) squares += (g - report.gap_mean) * (g - report.gap_mean);
  report.gap_cv = report.gap_mean > 0 ? std::sqrt(squares / double(gap.size())) / report.gap_mean : 0;
  report.gap_median = percentile(gap, 0.5);
  report.gap_p5 = percentile(gap, 0.05);
  report.gap_p95 = percentile(gap, 0.95);

  report.surface_samples = options.surface_samples;
  std::vector<double> coverage(samples.size());
  std::atomic<bool> uncovered = false; // the rest would each cost the reach's cells
  tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t s = range.begin(); s < range.end() && !uncovered; ++s) {
      coverage[s] = std::sqrt(grid.nearest_squared(samples[s], reach, [](int32_t, double) { return true; }));
      if (std::isinf(coverage[s])) uncovered = true;
    }
  });
  if (uncovered)
    throw InputError("the curves do not cover the surface: part of it lies farther than " + number(kReach) +
                     " spacing estimates (" + number(reach) + ") from them");
  const auto farthest = std::max_element(coverage.begin(), coverage.end());
  report.coverage_max = *farthest;
  report.farthest = samples[size_t(farthest - coverage.begin())];
  report.coverage_p99 = percentile(coverage, 0.99);
  return report;
}

} // namespace meander
