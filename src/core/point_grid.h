// A uniform grid of points for nearest-point and radius queries: what the evenness
// measure (evenness.h) and the relaxation (relax.h) look up neighbouring passes with.
// Internal to the library.
#pragma once

#include "meander/mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace meander {

// Points in a uniform grid of cubic cells, hashed into a power-of-two table of buckets
// by a counting sort (O(n)): bucket b holds the points ids[start[b] .. start[b+1]) at
// sorted[start[b] .. start[b+1]). Cells that share a bucket share its points, which costs
// time, never correctness: every point a query looks at is a true candidate.
class PointGrid {
public:
  // `cell` is raised so that the cell coordinates of `box`, which must hold the points
  // and the queries, fit in 21 bits.
  PointGrid(std::span<const Vec3> points, double cell, const Box3& box)
      : origin_(box.min), cell_(std::max(cell, max_side(box) / double(1 << 20))),
        shift_(64 - std::countr_zero(std::bit_ceil(std::max<size_t>(points.size(), 2)))) {
    std::vector<uint32_t> bucket(points.size());
    start_.assign((size_t(1) << (64 - shift_)) + 1, 0);
    for (size_t i = 0; i < points.size(); ++i) {
      const auto c = cell_of(points[i]);
      for (size_t a = 0; a < 3; ++a) {
        lo_[a] = std::min(lo_[a], c[a]);
        hi_[a] = std::max(hi_[a], c[a]);
      }
      bucket[i] = hash(c[0], c[1], c[2]);
      ++start_[bucket[i] + 1];
    }
    for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
    std::vector<int32_t> next(start_.begin(), start_.end() - 1);
    sorted_.resize(points.size());
    ids_.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const int32_t at = next[bucket[i]]++;
      sorted_[size_t(at)] = points[i];
      ids_[size_t(at)] = int32_t(i);
    }
  }

  // Calls f(rank) once for each point in the buckets of p's cell and the 26 around it:
  // every point within a cell of p, and others (the caller measures). `rank` is the
  // point's place in ids(), so that a caller can lay out what it needs of each point in
  // that order and read it in sequence.
  template <class F> void for_each_near(Vec3 p, F&& f) const {
    const auto c = cell_of(p);
    std::array<uint64_t, 27> buckets{};
    size_t count = 0;
    for (int64_t z = std::max(lo_[2], c[2] - 1); z <= std::min(hi_[2], c[2] + 1); ++z)
      for (int64_t y = std::max(lo_[1], c[1] - 1); y <= std::min(hi_[1], c[1] + 1); ++y)
        for (int64_t x = std::max(lo_[0], c[0] - 1); x <= std::min(hi_[0], c[0] + 1); ++x) buckets[count++] = hash(x, y, z);
    // Each bucket once, though cells may share one.
    std::sort(buckets.begin(), buckets.begin() + ptrdiff_t(count));
    const auto end = std::unique(buckets.begin(), buckets.begin() + ptrdiff_t(count));
    for (auto b = buckets.begin(); b != end; ++b)
      for (int32_t i = start_[*b]; i < start_[*b + 1]; ++i) f(size_t(i));
  }

  // The points' indices, by bucket: rank r of for_each_near is point ids()[r].
  std::span<const int32_t> ids() const { return ids_; }

  // The squared distance from p to the nearest point i within `radius` for which
  // accept(i, squared distance) holds; INFINITY if there is none. Visits the cells in
  // rings of growing Chebyshev distance around p's cell until the next ring lies farther
  // than the best or the radius.
  template <class Accept> double nearest_squared(Vec3 p, double radius, Accept&& accept) const {
    const std::array<double, 3> q = {double(p.x) - origin_.x, double(p.y) - origin_.y, double(p.z) - origin_.z};
    std::array<int64_t, 3> c{};
    std::array<double, 3> f{}; // p's offset in its cell
    double margin = INFINITY;  // from p to the nearest face of its cell
    int64_t first = 0;         // rings nearer than this miss the points' cells
    for (size_t a = 0; a < 3; ++a) {
      c[a] = int64_t(std::floor(q[a] / cell_));
      f[a] = q[a] - double(c[a]) * cell_;
      margin = std::min({margin, f[a], cell_ - f[a]});
      first = std::max({first, lo_[a] - c[a], c[a] - hi_[a]});
    }
    margin = std::max(margin, 0.0);
    // From p to the cells of coordinate x on axis a, squared.
    auto apart = [&](size_t a, int64_t x) {
      const double d = x < c[a]   ? double(c[a] - x - 1) * cell_ + f[a]
                       : x > c[a] ? double(x - c[a] - 1) * cell_ + cell_ - f[a]
                                  : 0.0;
      return d * d;
    };
    const double limit = radius * radius;
    double best = INFINITY;
    // Most cells of a ring lie beyond the best point found so far: skipped without a look
    // at their bucket.
    auto near = [&](double d2) { return d2 < best && d2 <= limit; };
    auto visit = [&](int64_t x, int64_t y, int64_t z, double yz) {
      if (!near(yz + apart(0, x))) return;
      const uint64_t b = hash(x, y, z);
      for (int32_t i = start_[b]; i < start_[b + 1]; ++i) {
        const Vec3 d = sorted_[size_t(i)] - p;
        const double d2 = dot(d, d);
        if (d2 < best && accept(ids_[size_t(i)], d2)) best = d2;
      }
    };
    for (int64_t k = first;; ++k) {
      const int64_t x0 = std::max(c[0] - k, lo_[0]), x1 = std::min(c[0] + k, hi_[0]);
      const int64_t y0 = std::max(c[1] - k, lo_[1]), y1 = std::min(c[1] + k, hi_[1]);
      const int64_t z0 = std::max(c[2] - k, lo_[2]), z1 = std::min(c[2] + k, hi_[2]);
      for (int64_t z = z0; z <= z1; ++z) {
        const double zz = apart(2, z);
        if (!near(zz)) continue;
        for (int64_t y = y0; y <= y1; ++y) {
          const double yz = zz + apart(1, y);
          if (!near(yz)) continue;
          if (z == c[2] - k || z == c[2] + k || y == c[1] - k || y == c[1] + k) {
            for (int64_t x = x0; x <= x1; ++x) visit(x, y, z, yz);
          } else {
            if (c[0] - k >= lo_[0] && c[0] - k <= hi_[0]) visit(c[0] - k, y, z, yz);
            if (c[0] + k >= lo_[0] && c[0] + k <= hi_[0]) visit(c[0] + k, y, z, yz);
          }
        }
      }
      // Points in the rings beyond k lie at least k cells and the margin away.
      const double reach = double(k) * cell_ + margin;
      if (best <= reach * reach || radius <= reach) break;
      // Rings 0 .. k hold every cell with points.
      if (c[0] - k <= lo_[0] && c[0] + k >= hi_[0] && c[1] - k <= lo_[1] && c[1] + k >= hi_[1] && c[2] - k <= lo_[2] &&
          c[2] + k >= hi_[2])
        break;
    }
    return best <= limit ? best : INFINITY;
  }

private:
  static double max_side(const Box3& box) {
    return std::max({double(box.max.x) - box.min.x, double(box.max.y) - box.min.y, double(box.max.z) - box.min.z});
  }
  std::array<int64_t, 3> cell_of(Vec3 p) const {
    return {int64_t(std::floor((double(p.x) - origin_.x) / cell_)),
            int64_t(std::floor((double(p.y) - origin_.y) / cell_)),
            int64_t(std::floor((double(p.z) - origin_.z) / cell_))};
  }
  // Fibonacci hashing of the cell's 63-bit key (21 bits a coordinate) into the table.
  uint64_t hash(int64_t x, int64_t y, int64_t z) const {
    const uint64_t key = uint64_t(x) | uint64_t(y) << 21 | uint64_t(z) << 42;
    return (key * 0x9e3779b97f4a7c15ULL) >> shift_;
  }

  Vec3 origin_;
  double cell_;
  int shift_;
  // The cells that hold points lie in [lo, hi] on each axis.
  std::array<int64_t, 3> lo_{INT64_MAX, INT64_MAX, INT64_MAX}, hi_{INT64_MIN, INT64_MIN, INT64_MIN};
  std::vector<int32_t> start_;
  std::vector<Vec3> sorted_;
  std::vector<int32_t> ids_;
};

} // namespace meander
