#include "meander/bridges.h"

#include "core/point_grid.h"
#include "core/segment_distance.h"
#include "core/union_find.h"
#include "meander/error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

namespace meander {

BridgePlan plan_bridges(const Polylines& centre, const BridgeOptions& options) {
  if (!(options.radius > 0) || !std::isfinite(options.radius))
    throw ParameterError("radius", " must be a positive number (got " + std::to_string(options.radius) + ")");
  if (!(options.max_stretch > 0) || !std::isfinite(options.max_stretch))
    throw ParameterError("bridges", " must be a positive length (got " + std::to_string(options.max_stretch) + ")");
  if (!(options.reach > 2 * options.radius) || !std::isfinite(options.reach))
    throw ParameterError("reach", " must be more than the wire's thickness (got " + std::to_string(options.reach) +
                                      " for a radius of " + std::to_string(options.radius) + ")");
  const size_t n = centre.points.size();
  const std::span<const double> inscribed = options.inscribed, extent = options.extent;
  for (const auto& [name, values] : {std::pair("inscribed", inscribed), std::pair("extent", extent)})
    if (!values.empty() && values.size() != n)
      throw ParameterError(name, " must hold one radius per centre point (got " + std::to_string(values.size()) + " for " +
                                     std::to_string(n) + ")");
  // About point i: the ball inside the wire, and how far the wire reaches.
  const auto ball = [&](size_t i) { return inscribed.empty() ? options.radius : inscribed[i]; };
  const auto reaches = [&](size_t i) { return extent.empty() ? options.radius : extent[i]; };
  double thickest = inscribed.empty() ? options.radius : 0, widest = extent.empty() ? options.radius : 0;
  for (const double b : inscribed) thickest = std::max(thickest, b);
  for (const double e : extent) widest = std::max(widest, e);
  std::vector<int32_t> curve_of(n);
  std::vector<double> arc(n), length(size_t(centre.size()));
  for (int32_t c = 0; c < centre.size(); ++c) {
    if (!centre.closed(c)) throw InputError("bridges: curve " + std::to_string(c) + " is open; a wire's curves are closed");
    const int32_t begin = centre.start[size_t(c)], end = centre.start[size_t(c) + 1];
    double s = 0;
    for (int32_t i = begin; i < end; ++i) {
      curve_of[size_t(i)] = c;
      arc[size_t(i)] = s;
      s += norm(to_double(centre.points[size_t(i + 1 < end ? i + 1 : begin)]) - to_double(centre.points[size_t(i)]));
    }
    length[size_t(c)] = s;
  }
  // How far apart two points of one curve lie along it (the shorter way round).
  const auto along = [&](size_t i, size_t j) {
    const double d = std::abs(arc[i] - arc[j]);
    return std::min(d, length[size_t(curve_of[i])] - d);
  };
  const auto point = [&](size_t i) { return to_double(centre.points[i]); };

  // The longest step between consecutive points.
  double step = 0;
  for (size_t i = 0; i < n; ++i) {
    const int32_t c = curve_of[i];
    const size_t next = int32_t(i) + 1 < centre.start[size_t(c) + 1] ? i + 1 : size_t(centre.start[size_t(c)]);
    step = std::max(step, norm(point(next) - point(i)));
  }
  // Each point's candidate: the nearest point of another pass within reach. A cell of the
  // grid is as wide as that and as what the clearance below looks for around a sample.
  // A strut and the gap kept beside it, in balls at its thinner end.
  constexpr double room = strut + 1.2;
  const double r = options.radius, reach = options.reach, clearance = widest + room * thickest;
  const PointGrid grid(centre.points, std::max(reach, clearance + (step + r) / 2), bounding_box(centre.points));
  const std::span<const int32_t> ids = grid.ids();
  std::vector<std::tuple<double, int32_t, int32_t>> candidates; // (distance, i, j)
  for (size_t i = 0; i < n; ++i) {
    if (!(ball(i) > 0)) continue;
    double best = reach;
    int32_t found = -1;
    grid.for_each_near(centre.points[i], [&](size_t rank) {
      const size_t j = size_t(ids[rank]);
      const double d = norm(point(j) - point(i));
      if (j == i || !(ball(j) > 0) || !(d <= best) || (d == best && found >= 0 && int32_t(j) > found)) return;
      if (curve_of[i] == curve_of[j] && !(along(i, j) > 1.4 * d)) return;
      best = d, found = int32_t(j);
    });
    if (found >= 0) candidates.emplace_back(best, int32_t(i), found);
  }
  std::sort(candidates.begin(), candidates.end());

  // Whether a bridge's axis keeps clear of every other part of the wire (points more
  // than reach + 2 radii along their curve from both ends: by the wire's extent there,
  // its strut and a gap of 1.2 balls; 3 radii for a tube) and of the bridges so far (by
  // 1.5 times the sum of their balls). Curve points are tested, widened by half the
  // longest step between them, around samples of the axis a radius apart.
  BridgePlan plan;
  std::vector<double> balls; // per bridge: the ball at its thinner end
  const auto clear = [&](size_t i, size_t j) {
    const Vec3 p = centre.points[i], q = centre.points[j];
    const double own = std::min(ball(i), ball(j));
    // Bridges no longer than reach whose middles lie farther apart than reach + clearance
    // keep that far apart.
    const double near = (reach + clearance) * (reach + clearance);
    for (size_t k = 0; k < plan.ends.size(); ++k) {
      const Vec3 s = centre.points[size_t(plan.ends[k][0])], t = centre.points[size_t(plan.ends[k][1])];
      const Vec3 offset = (s + t - p - q) * 0.5f;
      if (dot(offset, offset) < near && segment_distance(p, q, s, t) < 1.5 * (own + balls[k])) return false;
    }
    const double joined = reach + 2 * r;
    // A slab's strut runs inside it for half its extent at least: that much of the
    // axis is not looked at (a tube's is, all of it).
    const double length = norm(q - p);
    const float from = extent.empty() ? 0 : float(std::min(0.5, 0.5 * reaches(i) / length)),
                to = extent.empty() ? 0 : float(std::min(0.5, 0.5 * reaches(j) / length));
    const Vec3 a = p + (q - p) * from, b = q - (q - p) * to;
    const int samples = 1 + int(std::ceil(length / r));
    for (int k = 0; k <= samples; ++k) {
      bool ok = true;
      grid.for_each_near(a + (b - a) * (float(k) / float(samples)), [&](size_t rank) {
        const size_t m = size_t(ids[rank]);
        if ((curve_of[m] == curve_of[i] && along(m, i) < joined) || (curve_of[m] == curve_of[j] && along(m, j) < joined))
          return true;
        ok = segment_distance(centre.points[m], centre.points[m], a, b) >= reaches(m) + room * own + step / 2;
        return ok;
      });
      if (!ok) return false;
    }
    return true;
  };

  // blocked[i]: within `gap` along its curve of a bridge's end.
  std::vector<uint8_t> blocked(n, 0);
  const auto block = [&](size_t e, double gap) {
    const int32_t c = curve_of[e], begin = centre.start[size_t(c)], count = centre.start[size_t(c) + 1] - begin;
    blocked[e] = 1;
    for (int direction : {-1, 1})
      for (int32_t k = 1; k < count; ++k) {
        const size_t m = size_t(begin + ((int32_t(e) - begin + direction * k) % count + count) % count);
        if (!(along(m, e) < gap)) break;
        blocked[m] = 1;
      }
  };
  const auto accept = [&](size_t i, size_t j, double gap) {
    plan.ends.push_back({int32_t(i), int32_t(j)});
    balls.push_back(std::min(ball(i), ball(j)));
    plan.radii.push_back(strut * balls.back());
    block(i, gap), block(j, gap);
  };
  const double L = options.max_stretch;
  for (const auto& [d, i, j] : candidates)
    if (!blocked[size_t(i)] && !blocked[size_t(j)] && clear(size_t(i), size_t(j))) accept(size_t(i), size_t(j), L / 2);

  // The stretches between consecutive ends along each curve: (length, curve, the point
  // it starts at, the one it ends at; -1, -1 for a curve without ends).
  const auto stretches = [&] {
    std::vector<std::vector<int32_t>> at(size_t(centre.size()));
    for (const auto& bridge : plan.ends)
      for (int32_t e : bridge) at[size_t(curve_of[size_t(e)])].push_back(e);
    std::vector<std::tuple<double, int32_t, int32_t, int32_t>> result;
    for (int32_t c = 0; c < centre.size(); ++c) {
      std::vector<int32_t>& ends = at[size_t(c)];
      std::sort(ends.begin(), ends.end()); // points run along the curve
      if (ends.empty()) result.emplace_back(length[size_t(c)], c, -1, -1);
      for (size_t k = 0; k < ends.size(); ++k) {
        const int32_t from = ends[k], to = ends[(k + 1) % ends.size()];
        const double d = arc[size_t(to)] - arc[size_t(from)];
        result.emplace_back(k + 1 < ends.size() ? d : d + length[size_t(c)], c, from, to);
      }
    }
    return result;
  };
  // Into each stretch still longer than L, the best clear candidate at least L / 8 from
  // the ends around it (its other end anywhere clear), until none is added.
  for (bool added = true; added;) {
    added = false;
    std::fill(blocked.begin(), blocked.end(), 0);
    for (const auto& bridge : plan.ends)
      for (int32_t e : bridge) block(size_t(e), L / 8);
    // in_stretch[i]: 1 + the long stretch point i lies in, 0 if none; one bridge a round each.
    std::vector<int32_t> in_stretch(n, 0);
    int32_t long_ones = 0;
    for (const auto& [d, c, from, to] : stretches()) {
      if (!(d > L)) continue;
      ++long_ones;
      const int32_t begin = centre.start[size_t(c)], count = centre.start[size_t(c) + 1] - begin;
      for (int32_t k = from < 0 ? 0 : 1; k < count; ++k) {
        const int32_t i = begin + ((from < 0 ? 0 : from - begin) + k) % count;
        if (i == to) break;
        in_stretch[size_t(i)] = long_ones;
      }
    }
    std::vector<uint8_t> split(size_t(long_ones) + 1, 0);
    for (const auto& [d, i, j] : candidates) {
      const int32_t k = in_stretch[size_t(i)];
      if (k > 0 && !split[size_t(k)] && !blocked[size_t(i)] && clear(size_t(i), size_t(j))) {
        accept(size_t(i), size_t(j), L / 8);
        split[size_t(k)] = 1;
        added = true;
      }
    }
  }

  for (const auto& [d, c, from, to] : stretches()) plan.longest_stretch = std::max(plan.longest_stretch, d);
  UnionFind pieces(centre.size());
  int32_t joined = centre.size();
  for (const auto& [a, b] : plan.ends) joined -= pieces.unite(curve_of[size_t(a)], curve_of[size_t(b)]);
  plan.one_piece = joined <= 1;
  plan.every_pass_tied = plan.one_piece && plan.longest_stretch <= L;
  return plan;
}

PolygonMesh bridge_solids(const Polylines& centre, const BridgePlan& plan, int sides) {
  if (sides < 3) throw ParameterError("sides", " must be at least 3 (got " + std::to_string(sides) + ")");
  if (plan.radii.size() != plan.ends.size())
    throw ParameterError("radii", " must hold one radius per bridge (got " + std::to_string(plan.radii.size()) + " for " +
                                      std::to_string(plan.ends.size()) + ")");
  PolygonMesh mesh;
  for (size_t bridge = 0; bridge < plan.ends.size(); ++bridge) {
    const auto [a, b] = plan.ends[bridge];
    const double width = plan.radii[bridge];
    const Vec3d p = to_double(centre.points[size_t(a)]), q = to_double(centre.points[size_t(b)]);
    const Vec3d axis = (q - p) * (1 / norm(q - p));
    const Vec3d other = std::abs(axis.x) < 0.6 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    Vec3d u = cross(axis, other);
    u = u * (1 / norm(u));
    const Vec3d v = cross(axis, u);
    // Three rings, at the ends and in the middle: the middle one outside the wire, so
    // that the strut's own thickness is measured where the wire's report casts its rays.
    const int32_t first = mesh.num_vertices();
    for (const Vec3d at : {p, (p + q) * 0.5, q})
      for (int k = 0; k < sides; ++k) {
        const double angle = 2 * M_PI * k / sides;
        mesh.positions.push_back(to_float(at + u * (width * std::cos(angle)) + v * (width * std::sin(angle))));
      }
    mesh.positions.push_back(to_float(p));
    mesh.positions.push_back(to_float(q));
    const int32_t low = first + 3 * sides, high = low + 1;
    // Counter-clockwise about the axis (u, v, axis right-handed): outward quads run
    // ring k, k+1 then the next ring's k+1, k; the caps face away from each other.
    for (int k = 0; k < sides; ++k) {
      const int32_t k1 = (k + 1) % sides;
      for (int32_t ring = first; ring < first + 2 * sides; ring += sides)
        mesh.add_face({ring + k, ring + k1, ring + sides + k1, ring + sides + k});
      mesh.add_face({low, first + k1, first + k});
      mesh.add_face({high, first + 2 * sides + k, first + 2 * sides + k1});
    }
  }
  return mesh;
}

} // namespace meander
