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
#include <type_traits>
#include <vector>

namespace meander {

// Points in a uniform grid of cubic cells, put into a power-of-two table of buckets by a
// counting sort (O(n)): bucket b holds the points ids[start[b] .. start[b+1]) at
// sorted[start[b] .. start[b+1]). A cell's bucket is its coordinates modulo the table's
// sides, so a cell and its 26 neighbours never share one; far cells may, which costs time,
// never correctness: every point a query looks at is a true candidate.
class PointGrid {
public:
  // `box` must hold the points and the queries; `cell` is raised to a millionth of its
  // largest side, so that a cell's coordinates stay far from overflowing.
  PointGrid(std::span<const Vec3> points, double cell, const Box3& box)
      : origin_(box.min), cell_(std::max(cell, max_side(box) / double(1 << 20))) {
    // About as many buckets as points, at least 64: at least 2 bits of each coordinate.
    const int bits = std::max(6, std::countr_zero(std::bit_ceil(std::max<size_t>(points.size(), 2))));
    bits_ = {(bits + 2) / 3, (bits - (bits + 2) / 3 + 1) / 2, 0};
    bits_[2] = bits - bits_[0] - bits_[1];
    std::vector<uint32_t> bucket(points.size());
    start_.assign((size_t(1) << bits) + 1, 0);
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

  // Calls f(rank) once for each point in the buckets of p's cell and the 26 around it,
  // p's own cell first: every point within a cell of p, and others (the caller
  // measures). `rank` is the point's place in ids(), so that a caller can lay out what it
  // needs of each point in that order and read it in sequence. An f that returns bool
  // stops the search by returning false.
  template <class F> void for_each_near(Vec3 p, F&& f) const {
    const auto c = cell_of(p);
    auto visit = [&](int64_t x, int64_t y, int64_t z) {
      if (x < lo_[0] || x > hi_[0] || y < lo_[1] || y > hi_[1] || z < lo_[2] || z > hi_[2]) return true;
      const uint64_t b = hash(x, y, z);
      for (int32_t i = start_[b]; i < start_[b + 1]; ++i) {
        if constexpr (std::is_same_v<decltype(f(size_t(i))), bool>) {
          if (!f(size_t(i))) return false;
        } else {
          f(size_t(i));
        }
      }
      return true;
    };
    if (!visit(c[0], c[1], c[2])) return;
    for (int64_t z = c[2] - 1; z <= c[2] + 1; ++z)
      for (int64_t y = c[1] - 1; y <= c[1] + 1; ++y)
        for (int64_t x = c[0] - 1; x <= c[0] + 1; ++x)
          if ((x != c[0] || y != c[1] || z != c[2]) && !visit(x, y, z)) return;
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
  // The low bits_[a] bits of each coordinate, side by side.
  uint64_t hash(int64_t x, int64_t y, int64_t z) const {
    auto low = [this](int64_t v, size_t a) { return uint64_t(v) & ((uint64_t(1) << bits_[a]) - 1); };
    return low(x, 0) | low(y, 1) << bits_[0] | low(z, 2) << (bits_[0] + bits_[1]);
  }

  Vec3 origin_;
  double cell_;
  std::array<int, 3> bits_{};
  // The cells that hold points lie in [lo, hi] on each axis.
  std::array<int64_t, 3> lo_{INT64_MAX, INT64_MAX, INT64_MAX}, hi_{INT64_MIN, INT64_MIN, INT64_MIN};
  std::vector<int32_t> start_;
  std::vector<Vec3> sorted_;
  std::vector<int32_t> ids_;
};

} // namespace meander
