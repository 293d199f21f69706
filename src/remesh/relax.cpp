#include "meander/relax.h"

#include "core/point_grid.h"
#include "core/surface_samples.h"
#include "meander/connectivity.h"
#include "meander/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace meander {

namespace {

// As in evenness.h: another pass lies farther along the curve than 1.4 times the
// straight distance; nearer points are the same stretch.
constexpr double kPassRatio = 1.4;
// Points per spacing along the curve: fine enough that a quarter of a gap, the most a
// point moves, is more than half a step, so passes cannot slip between points.
constexpr double kStepsPerSpacing = 4;
// Passes are looked for this many spacings around a point; a side with none that near
// counts as a pass this far, so a pass beside a hole moves into it. This sets the scale
// the gaps settle at: 1.25 gives a median gap of 0.98 to 1.0 spacings (1.5 gave 1.1).
constexpr double kReach = 1.25;
// A side with only the curve's own bend on it (the inside of a hairpin, where no point is
// another pass by the 1.4 rule) counts as a pass this many spacings away, so the tip of a
// hairpin keeps its distance from the pass beyond it and neither retracts nor grows.
constexpr double kBend = 0.9;
// How far a point moves toward the middle of its neighbouring passes per iteration, and
// how far toward the middle of its two curve neighbours (which keeps the curve smooth).
constexpr double kCentre = 0.5;
constexpr double kFairing = 0.1;
// Passes whose normals differ by more than 120 degrees lie on two sides of a thin part.
constexpr double kOtherSide = -0.5;
// Rounds of [1 2 1] / 4 along the curve that spread a point's move over half a spacing
// (sqrt(rounds / 2) points, a quarter spacing apart), or single points would buckle into
// the gaps.
constexpr int kSmoothing = 8;
// A surface point farther than kPocket spacings from the curve is a pocket: it pulls the
// nearest point of the curve toward it, kPull times the way that brings it within
// kPocket, every other round (the tips of branches grow into the pockets beyond them,
// and thin parts' tips get covered). Looked for at kSamples surface points per square
// spacing: 4 left the farthest point at 1.0 to 1.1 spacings, 8 at 0.9 to 1.0; pulling
// every round evened the coverage a little more but the gaps less.
constexpr double kPocket = 0.5;
constexpr double kPull = 1.5;
constexpr double kSamples = 8;
// A needle: a hairpin pinched until its arms lie nearer than kNeedle spacings, within
// kNeedleLength spacings along the curve. It grows where the curve moved onto the input
// jumps across a thin part that the even mesh strayed from, and would leave a wire no
// room; it is cut off where its arms meet every round (cut only at the end, the pockets
// it left stayed open).
constexpr double kNeedle = 0.25;
constexpr double kNeedleLength = 4;
// A gap between consecutive points is bridged along the surface by a way at most this
// many times as long.
constexpr double kDetour = 3;
// Segments longer than this many steps are taken to cross a thin part, and not looked at
// for crossings.
constexpr double kLongest = 2;

Vec3d normalized(Vec3d v) {
  const double length = norm(v);
  return length > 0 ? v * (1 / length) : Vec3d{};
}

struct Curves {
  std::vector<ClosestPoints::Hit> points; // on the surface
  std::vector<int32_t> start{0};
  int32_t size() const { return int32_t(start.size()) - 1; }
};

// Points on the boundary edges of the surface, `step` apart or closer.
std::vector<Vec3> boundary_points(const PolygonMesh& surface, double step) {
  const Connectivity connectivity = build_connectivity(surface);
  std::vector<Vec3> points;
  for (int32_t e = 0; e < connectivity.num_edges(); ++e) {
    if (connectivity.edge_degree(e) != 1) continue;
    const auto [a, b] = connectivity.edge_vertices[size_t(e)];
    const Vec3d pa = to_double(surface.positions[size_t(a)]), pb = to_double(surface.positions[size_t(b)]);
    const int pieces = std::max(1, int(std::ceil(norm(pb - pa) / step)));
    for (int k = 0; k < pieces; ++k) points.push_back(to_float(pa + (pb - pa) * (double(k) / pieces)));
  }
  return points;
}

// `out`: each curve with points about `step` apart: a stretch longer than 1.5 steps gets
// points between (on the surface), and a point nearer than half a step to the last one
// kept is dropped, so the points keep their order. A curve shorter than 4 steps (on a
// component smaller than the spacing) keeps its points, which would otherwise be too few
// to close.
void resample(const Curves& curves, double step, const ClosestPoints& closest, Curves& out) {
  out.points.clear();
  out.start.assign(1, 0);
  // The points between a and b: the closest points of the chord's, a step apart (a
  // point within half a step of the one before is left out), or, where those leave a gap
  // (a chord across a part thinner than the spacing, whose closest points lie on its two
  // sides), points along the surface's way round the part's edge.
  std::vector<ClosestPoints::Hit> chord;
  auto fill = [&](const ClosestPoints::Hit& a, const ClosestPoints::Hit& b, double d) {
    const int pieces = int(std::floor(d / step + 0.5));
    if (pieces < 2) return;
    chord.clear();
    double widest = 0;
    const ClosestPoints::Hit* last = &a;
    for (int m = 1; m < pieces; ++m) {
      const ClosestPoints::Hit h = closest.closest_hit(a.point + (b.point - a.point) * (double(m) / pieces), *last);
      const double gap = norm(h.point - last->point);
      if (gap < 0.5 * step) continue;
      widest = std::max(widest, gap);
      chord.push_back(h);
      last = &chord.back();
    }
    if (std::max(widest, norm(b.point - last->point)) > 2 * step)
      if (std::vector<ClosestPoints::Hit> way = closest.path(a, b, step, kDetour * d); !way.empty()) chord = std::move(way);
    while (!chord.empty() && norm(b.point - chord.back().point) < 0.5 * step) chord.pop_back();
    out.points.insert(out.points.end(), chord.begin(), chord.end());
  };
  for (int32_t k = 0; k < curves.size(); ++k) {
    const int32_t first = curves.start[size_t(k)], end = curves.start[size_t(k) + 1];
    const size_t begin = out.points.size();
    double length = 0;
    for (int32_t i = first; i < end; ++i)
      length += norm(curves.points[size_t(i + 1 == end ? first : i + 1)].point - curves.points[size_t(i)].point);
    if (length < 4 * step) {
      out.points.insert(out.points.end(), curves.points.begin() + first, curves.points.begin() + end);
      out.start.push_back(int32_t(out.points.size()));
      continue;
    }
    for (int32_t i = first; i < end; ++i) {
      const ClosestPoints::Hit& p = curves.points[size_t(i)];
      if (out.points.size() > begin) {
        const ClosestPoints::Hit last = out.points.back();
        const double d = norm(p.point - last.point);
        if (d < 0.5 * step && end - i > 1) continue;
        fill(last, p, d);
      }
      out.points.push_back(p);
    }
    // The closing stretch, back to the first point.
    const ClosestPoints::Hit last = out.points.back(), p = out.points[begin];
    fill(last, p, norm(p.point - last.point));
    out.start.push_back(int32_t(out.points.size()));
  }
}

// Whether segments a0-a1 and b0-b1, with the surface's normals na and nb at a0 and b0,
// cross on the surface: seen along the normals' mean, they cross, and there they are
// less than `near` apart. Passes on two sides of a thin part (normals more than 60
// degrees apart) do not.
bool cross_on_surface(Vec3d a0, Vec3d a1, Vec3d b0, Vec3d b1, Vec3d na, Vec3d nb, double near) {
  if (dot(na, nb) < 0.5) return false;
  const Vec3d n = normalized(na + nb);
  auto flat = [&](Vec3d v) { return v - n * dot(v, n); };
  const Vec3d u = flat(a1 - a0), v = flat(b1 - b0), w = flat(b0 - a0);
  const double denominator = dot(cross(u, v), n);
  if (denominator == 0) return false;
  // a0 + s u meets b0 + t v.
  const double s = dot(cross(w, v), n) / denominator, t = dot(cross(w, u), n) / denominator;
  if (!(s > 0 && s < 1 && t > 0 && t < 1)) return false;
  return norm((a0 + (a1 - a0) * s) - (b0 + (b1 - b0) * t)) < near;
}

// The boundary of the surface, in a grid of cells `reach` wide, its points by rank.
struct Walls {
  PointGrid grid;
  std::vector<Vec3d> by_rank;
};

// A point of the curves as the neighbour search reads it, by rank in the grid.
struct Near {
  Vec3d normal;
  double along;
  int32_t curve, index;
};

// What a round works in, kept from round to round: allocated anew, these arrays were
// mapped and faulted in again every round (two more of them made relaxing a 1M-face
// sphere half again as slow).
struct Round {
  std::vector<Vec3d> at, point_by_rank, across;
  std::vector<Vec3> cells;
  std::vector<int32_t> curve_of, needle_end, crossing, nearest_of, order;
  std::vector<double> along, segment, length, centre, limit, sample_distance, pull, smoothed;
  std::vector<Near> by_rank;
  std::vector<uint8_t> kept;
  std::vector<ClosestPoints::Hit> moved;
};

// `out`: one move of every point toward the middle of its neighbouring passes, without the
// points of needles and without crossings of a curve with itself. Moved onto the input
// by the closest point, a curve made on the even mesh folds over itself where the mesh
// strays from the input by more than the gap between passes (fertility's arm at 1/30),
// and the moves, which keep passes from crossing, would keep the crossing; rarely, a
// stretch filled in across a gap crosses another pass. Where segments i and j > i of a
// curve cross, its points i + 1 to j are reversed (a 2-opt move): still one closed curve,
// without that crossing. `box` holds the surface, with a cell of margin.
void relax(const Curves& curves, const Walls& walls, std::span<const Vec3> samples, const Box3& box, double spacing,
           const ClosestPoints& closest, Round& round, Curves& out) {
  const double reach = kReach * spacing;
  const double bend = kBend * spacing;
  const double step = spacing / kStepsPerSpacing;
  const size_t n = curves.points.size();
  std::vector<Vec3d>& at = round.at;
  std::vector<Vec3>& cells = round.cells;
  at.resize(n);
  cells.resize(n);
  for (size_t i = 0; i < n; ++i) {
    at[i] = curves.points[i].point;
    cells[i] = to_float(at[i]);
  }
  const PointGrid grid(cells, reach, box);
  // Each point's curve, its distance along it from the curve's first point, and its
  // segment's length, to the next point.
  std::vector<int32_t>& curve_of = round.curve_of;
  std::vector<double>&along = round.along, &segment = round.segment, &length = round.length;
  curve_of.resize(n);
  along.resize(n);
  segment.resize(n);
  length.resize(size_t(curves.size()));
  for (int32_t k = 0; k < curves.size(); ++k) {
    double s = 0;
    const int32_t first = curves.start[size_t(k)], last = curves.start[size_t(k) + 1] - 1;
    for (int32_t i = first; i <= last; ++i) {
      segment[size_t(i)] = norm(at[size_t(i == last ? first : i + 1)] - at[size_t(i)]);
      curve_of[size_t(i)] = k;
      along[size_t(i)] = s;
      s += segment[size_t(i)];
    }
    length[size_t(k)] = s;
  }
  // By rank in the grid: the points apart from the rest, which only the few within
  // reach of a query need.
  std::vector<Vec3d>& point_by_rank = round.point_by_rank;
  std::vector<Near>& by_rank = round.by_rank;
  point_by_rank.resize(n);
  by_rank.resize(n);
  for (size_t rank = 0; rank < n; ++rank) {
    const size_t i = size_t(grid.ids()[rank]);
    point_by_rank[rank] = at[i];
    by_rank[rank] = {curves.points[i].normal, along[i], curve_of[i], int32_t(i)};
  }
  // Each point's direction across the curve on the surface, the move toward the middle
  // of its neighbouring passes, and the most it may move.
  std::vector<Vec3d>& across = round.across;
  std::vector<double>&centre = round.centre, &limit = round.limit;
  across.resize(n);
  centre.resize(n);
  limit.resize(n);
  // The point farthest ahead along the curve that closes a needle with each point (or
  // the point itself), and the first segment after each point's that crosses it (or -1).
  std::vector<int32_t>&needle_end = round.needle_end, &crossing = round.crossing;
  needle_end.resize(n);
  crossing.resize(n);
  auto neighbours = [&](size_t i) {
    const int32_t k = curve_of[i], first = curves.start[size_t(k)], end = curves.start[size_t(k) + 1];
    return std::pair(size_t(int32_t(i) == first ? end - 1 : int32_t(i) - 1),
                     size_t(int32_t(i) + 1 == end ? first : int32_t(i) + 1));
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const int32_t k = curve_of[i];
      const auto [before, after] = neighbours(i);
      const Vec3d p = at[i], normal = curves.points[i].normal;
      across[i] = normalized(cross(normal, at[after] - at[before]));
      double nearest = reach, plus = reach, minus = reach;
      bool plus_bend = false, minus_bend = false;
      double needle_ahead = 0;
      needle_end[i] = int32_t(i);
      auto pass = [&](Vec3d q, double distance_as) {
        const double side = dot(q - p, across[i]);
        (side > 0 ? plus : minus) = std::min(side > 0 ? plus : minus, distance_as);
      };
      grid.for_each_near(cells[i], [&](size_t rank) {
        const Vec3d q = point_by_rank[rank];
        const double d2 = dot(q - p, q - p);
        if (d2 >= reach * reach) return;
        const Near& near = by_rank[rank];
        if (size_t(near.index) == i) return;
        const double d = std::sqrt(d2);
        if (near.curve == k) {
          const double gone = std::abs(along[i] - near.along);
          const double a = std::min(gone, length[size_t(k)] - gone);
          const double ahead = near.along >= along[i] ? near.along - along[i] : near.along + length[size_t(k)] - along[i];
          if (d < kNeedle * spacing && ahead <= kNeedleLength * spacing && ahead > kPassRatio * d && ahead > needle_ahead) {
            needle_ahead = ahead;
            needle_end[i] = near.index;
          }
          if (a <= kPassRatio * d) {
            // The inside of a hairpin: the curve's own bend, not a hole.
            const double side = dot(q - p, across[i]);
            if (a > 0.5 * spacing && std::abs(side) > 0.5 * d) (side > 0 ? plus_bend : minus_bend) = true;
            return;
          }
        }
        nearest = std::min(nearest, d);
        if (dot(normal, near.normal) >= kOtherSide) pass(q, d);
      });
      // The boundary stands for a pass twice as far, so passes keep half a spacing from it.
      walls.grid.for_each_near(cells[i], [&](size_t rank) {
        const Vec3d q = walls.by_rank[rank];
        const double d = norm(q - p);
        if (d >= reach) return;
        nearest = std::min(nearest, d);
        pass(q, 2 * d);
      });
      if (plus_bend && plus == reach) plus = bend;
      if (minus_bend && minus == reach) minus = bend;
      centre[i] = across[i] == Vec3d{} ? 0 : kCentre * (plus - minus) / 2;
      limit[i] = nearest / 4;
    }
  });
  // The first segment after each point's that crosses it, looked for only where another
  // pass comes within two segments (limit is a quarter of the nearest one's distance).
  // Segments longer than kLongest steps, left across thin parts, are not looked at.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      crossing[i] = -1;
      const size_t after = neighbours(i).second;
      if (4 * limit[i] >= segment[i] + kLongest * step || segment[i] > kLongest * step) continue;
      grid.for_each_near(cells[i], [&](size_t rank) {
        const int32_t j = by_rank[rank].index;
        if (j <= int32_t(i) + 1 || by_rank[rank].curve != curve_of[i] || segment[size_t(j)] > kLongest * step ||
            (crossing[i] >= 0 && j >= crossing[i]))
          return;
        const size_t after_j = neighbours(size_t(j)).second;
        if (after_j != i && cross_on_surface(at[i], at[after], at[size_t(j)], at[after_j], curves.points[i].normal,
                                             by_rank[rank].normal, step))
          crossing[i] = j;
      });
    }
  });
  // Pockets: a surface sample farther than kPocket spacings from every point pulls the
  // nearest one (the lowest numbered of equals) toward it.
  const double pocket = kPocket * spacing;
  std::vector<int32_t>& nearest_of = round.nearest_of;
  std::vector<double>& sample_distance = round.sample_distance;
  nearest_of.assign(samples.size(), -1);
  sample_distance.assign(samples.size(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 256), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t s = range.begin(); s < range.end(); ++s) {
      const Vec3d q = to_double(samples[s]);
      double best = reach * reach;
      // A point within kPocket ends the search: the sample is no pocket.
      grid.for_each_near(samples[s], [&](size_t rank) {
        const Vec3d d = point_by_rank[rank] - q;
        const double d2 = dot(d, d);
        if (d2 <= pocket * pocket) {
          nearest_of[s] = -1;
          return false;
        }
        if (d2 < best || (d2 == best && nearest_of[s] >= 0 && by_rank[rank].index < nearest_of[s])) {
          best = d2;
          nearest_of[s] = by_rank[rank].index;
        }
        return true;
      });
      sample_distance[s] = std::sqrt(best);
    }
  });
  std::vector<double>& pull = round.pull;
  pull.assign(n, 0);
  for (size_t s = 0; s < samples.size(); ++s) {
    const int32_t j = nearest_of[s];
    if (j < 0) continue;
    const double along_across = dot(to_double(samples[s]) - at[size_t(j)], across[size_t(j)]);
    const double want = along_across * (sample_distance[s] - pocket) / sample_distance[s];
    if (std::abs(want) > std::abs(pull[size_t(j)])) pull[size_t(j)] = want;
  }
  for (size_t i = 0; i < n; ++i) centre[i] += kPull * pull[i];
  // Points of a pass move together.
  std::vector<double>& smoothed = round.smoothed;
  smoothed.resize(n);
  for (int pass = 0; pass < kSmoothing; ++pass) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t i = range.begin(); i < range.end(); ++i) {
        const auto [before, after] = neighbours(i);
        smoothed[i] = 0.5 * centre[i] + 0.25 * (centre[before] + centre[after]);
      }
    });
    centre.swap(smoothed);
  }
  // Needles are cut in order along each curve, the points between a point and its
  // needle's end dropped; a curve a few needles long is left as it is, lest a cut take
  // most of it.
  std::vector<uint8_t>& kept = round.kept;
  kept.assign(n, 1);
  for (int32_t k = 0; k < curves.size(); ++k) {
    if (length[size_t(k)] < 4 * kNeedleLength * spacing) continue;
    const int32_t first = curves.start[size_t(k)], m = curves.start[size_t(k) + 1] - first;
    for (int32_t i = first; i < first + m; ++i)
      if (kept[size_t(i)] && needle_end[size_t(i)] != i)
        for (int32_t j = (i - first + 1) % m; first + j != needle_end[size_t(i)]; j = (j + 1) % m) kept[size_t(first + j)] = 0;
  }
  std::vector<ClosestPoints::Hit>& moved = round.moved;
  moved.resize(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      if (!kept[i]) continue;
      const auto [before, after] = neighbours(i);
      const Vec3d p = at[i];
      const Vec3d middle = (at[before] + at[after]) * 0.5;
      const double move = std::clamp(centre[i] + kFairing * dot(middle - p, across[i]), -limit[i], limit[i]);
      moved[i] = closest.nearby_hit(p + across[i] * move, curves.points[i]);
      if (moved[i].normal == Vec3d{}) moved[i].normal = curves.points[i].normal;
    }
  });
  // Crossings are undone in order, each reversal apart from the others (the rest wait
  // for the next round) and between kept points.
  std::vector<int32_t>& order = round.order;
  order.resize(n);
  std::iota(order.begin(), order.end(), 0);
  int32_t free_from = 0;
  for (int32_t i = 0; i < int32_t(n); ++i) {
    const int32_t j = crossing[size_t(i)];
    if (j < 0 || i < free_from || !kept[size_t(i)] || !kept[neighbours(size_t(i)).second] || !kept[size_t(j)] ||
        !kept[neighbours(size_t(j)).second])
      continue;
    std::reverse(order.begin() + i + 1, order.begin() + j + 1);
    free_from = j + 1;
  }
  out.points.clear();
  out.start.assign(1, 0);
  for (int32_t k = 0; k < curves.size(); ++k) {
    for (int32_t i = curves.start[size_t(k)]; i < curves.start[size_t(k) + 1]; ++i)
      if (kept[size_t(order[size_t(i)])]) out.points.push_back(moved[size_t(order[size_t(i)])]);
    out.start.push_back(int32_t(out.points.size()));
  }
}

} // namespace

RelaxedCurves relax_curves(const Polylines& curves, const PolygonMesh& surface, const ClosestPoints& closest,
                           const RelaxOptions& options, Progress* progress) {
  if (!(options.spacing > 0 && std::isfinite(options.spacing)))
    throw ParameterError("spacing", " must be a positive number to relax a curve");
  if (options.iterations < 0) throw ParameterError("iterations", " must be at least 0");
  const double step = options.spacing / kStepsPerSpacing;
  for (int32_t k = 0; k < curves.size(); ++k)
    if (!curves.closed(k)) throw InputError("curve " + std::to_string(k) + " is open: only closed curves are relaxed");
  Curves work{.points = std::vector<ClosestPoints::Hit>(curves.points.size()), .start = curves.start};
  // Each query hinted by the last one's answer: points next to each other along a curve
  // are near on the surface.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, curves.points.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
    ClosestPoints::Hit last;
    for (size_t i = range.begin(); i < range.end(); ++i)
      last = work.points[i] = closest.closest_hit(to_double(curves.points[i]), last);
  });
  // Points stay on the surface: its box, grown by a cell, holds them and the queries.
  const double reach = kReach * options.spacing;
  Box3 box = bounding_box(surface.positions);
  box.extend(box.min - Vec3{1, 1, 1} * float(reach));
  box.extend(box.max + Vec3{1, 1, 1} * float(reach));
  const std::vector<Vec3> boundary = boundary_points(surface, step);
  Walls walls{.grid = PointGrid(boundary, reach, box), .by_rank = std::vector<Vec3d>(boundary.size())};
  for (size_t rank = 0; rank < boundary.size(); ++rank)
    walls.by_rank[rank] = to_double(boundary[size_t(walls.grid.ids()[rank])]);
  // Where pockets are looked for: surface samples, area-weighted, kSamples per square spacing.
  const std::vector<double> cumulative = cumulative_areas(surface);
  const double samples_wanted = cumulative.empty() ? 0 : kSamples * cumulative.back() / (options.spacing * options.spacing);
  const std::vector<Vec3> samples =
      surface_samples(surface, cumulative, int32_t(std::min(samples_wanted, double(INT32_MAX))), 1);
  Curves moved;
  Round round;
  resample(work, step, closest, moved);
  std::swap(work, moved);
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    advance_progress(progress, double(iteration) / options.iterations);
    relax(work, walls, iteration % 2 == 0 ? samples : std::span<const Vec3>(), box, options.spacing, closest, round, moved);
    resample(moved, step, closest, work);
  }
  RelaxedCurves out;
  out.curves.points.reserve(work.points.size());
  out.normals.reserve(work.points.size());
  for (const ClosestPoints::Hit& p : work.points) {
    out.curves.points.push_back(to_float(p.point));
    out.normals.push_back(to_float(p.normal));
  }
  out.curves.start = work.start;
  return out;
}

} // namespace meander
