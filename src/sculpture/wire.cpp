#include "meander/wire.h"

#include "core/segment_distance.h"

#include "meander/error.h"
#include "meander/printability.h"
#include "meander/subdivide.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

namespace meander {

WireShape parse_wire_shape(std::string_view name) {
  if (name == "wire") return WireShape::wire;
  if (name == "ribbon") return WireShape::ribbon;
  throw UsageError("unknown wire shape '" + std::string(name) + "' (expected wire or ribbon)");
}

namespace {

Vec3 normalized(Vec3 v) {
  const double n = norm(v);
  return n > 0 ? v * float(1.0 / n) : Vec3{};
}

bool contains(const std::array<int32_t, 3>& t, int32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

// How each triangle of the cycle sits on the ladder. Triangle (p, apex, n) has its two
// quad sides p-apex and apex-n; the curve enters through one and leaves through the
// other. The corners of the trapezoid next to the apex form one rail, the others the
// second rail; `apex_right` says which side of the direction of travel the apex rail
// is on. The unit normal `up` is the triangle's normal signed so that, seen from it, the
// right rail is on the right: the same side of the surface all along an orientable cycle.
struct Ladder {
  std::vector<uint8_t> entry_is_p;
  std::vector<uint8_t> apex_right;
  std::vector<Vec3> up;
  std::vector<uint8_t> mobius; // per cycle: the rails swap where the cycle closes
  // Per cycle: every triangle is oriented the ladder's way, as on an orientable surface.
  // There the surface normal is taken smooth, from the vertex normals: a triangle's own
  // normal flips across the sharp folds that coarse meshes' quads make, and a frame
  // following it would twist the wire into itself.
  std::vector<uint8_t> coherent;
  std::vector<Vec3> vertex_normal; // per quad-mesh vertex, area-weighted, not normalized
};

// The unit surface normal at vertex v of triangle i (of cycle c), on the ladder's up side.
Vec3 surface_normal(const Ladder& l, int32_t c, size_t i, int32_t v) {
  if (l.coherent[size_t(c)])
    if (const Vec3 n = normalized(l.vertex_normal[size_t(v)]); norm(n) > 0) return n;
  return l.up[i];
}

Ladder make_ladder(const QuadMesh& quads, const TriangleCycle& cycle) {
  const size_t n = cycle.order.size();
  Ladder l;
  l.entry_is_p.resize(n);
  l.apex_right.resize(n);
  l.up.resize(n);
  l.mobius.resize(size_t(cycle.num_cycles()));
  l.coherent.resize(size_t(cycle.num_cycles()));
  l.vertex_normal.resize(quads.positions.size());
  auto tri = [&](size_t i) { return cycle_triangle(quads, cycle.order[i]); };
  for (int32_t c = 0; c < cycle.num_cycles(); ++c) {
    const size_t first = size_t(cycle.cycle_start[size_t(c)]), count = size_t(cycle.cycle_start[size_t(c) + 1]) - first;
    auto at = [&](size_t k) { return tri(first + k % count); };
    // Travelling from triangle k-1 into k: the apex rail stays on its side when both
    // apexes coincide, and changes side when the apex of k is the other end of the
    // shared quad side.
    auto continue_rail = [&](size_t k, bool prev_right) {
      return at(k)[1] == at(k + count - 1)[1] ? prev_right : !prev_right;
    };
    for (size_t k = 0; k < count; ++k) {
      const auto t = at(k);
      const size_t i = first + k;
      l.entry_is_p[i] = contains(at(k + count - 1), t[0]);
      l.apex_right[i] = k == 0 ? l.entry_is_p[i] : continue_rail(k, l.apex_right[i - 1]);
      const Vec3 p = quads.positions[size_t(t[0])], a = quads.positions[size_t(t[1])], q = quads.positions[size_t(t[2])];
      const Vec3 area = cross(a - p, q - p), normal = normalized(area);
      l.up[i] = l.apex_right[i] == l.entry_is_p[i] ? normal : normal * -1.0f;
      for (int32_t v : t) l.vertex_normal[size_t(v)] = l.vertex_normal[size_t(v)] + area;
    }
    l.mobius[size_t(c)] = continue_rail(count, l.apex_right[first + count - 1]) != l.apex_right[first];
    bool coherent = !l.mobius[size_t(c)];
    for (size_t k = first; k < first + count && coherent; ++k) coherent = l.apex_right[k] == l.entry_is_p[k];
    l.coherent[size_t(c)] = coherent;
    // A zero-area triangle has no normal of its own: it borrows its predecessor's.
    size_t valid = count;
    for (size_t k = 0; k < count && valid == count; ++k)
      if (norm(l.up[first + k]) > 0) valid = k;
    if (valid == count) throw TopologyError("every triangle of cycle " + std::to_string(c) + " has zero area: no surface normal to build a wire on");
    for (size_t j = 1; j < count; ++j) {
      const size_t k = first + (valid + j) % count, prev = first + (valid + j - 1) % count;
      if (norm(l.up[k]) == 0) l.up[k] = (valid + j) % count == 0 && l.mobius[size_t(c)] ? l.up[prev] * -1.0f : l.up[prev];
    }
  }
  return l;
}

// The normal of the tube's cross-section at point b between a and c: the bisector of the
// directions in and out, so that on a sharp turn the two segments' tubes stay on either
// side of the section (a central difference would tilt it into one of them). Zero when
// b coincides with a neighbour or the curve turns straight back.
Vec3 section_normal(Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 in = normalized(b - a), out = normalized(c - b);
  if (norm(in) == 0 || norm(out) == 0) return in + out;
  return normalized(in + out);
}

// Quads between consecutive rings of `width` vertices (ring i starts at first + i *
// width), closing the last ring onto the first with its vertex j joined to the first
// ring's vertex (j + shift) mod width. Open rings (a ribbon's rungs) get no quad from
// their last vertex back to their first. With `keep`, only the rings i with keep[i] set
// get their quads to the next ring.
void connect_rings(PolygonMesh& mesh, int32_t first, int32_t rings, int32_t width, bool closed_ring, int32_t shift,
                   const uint8_t* keep = nullptr) {
  for (int32_t i = 0; i < rings; ++i) {
    if (keep && !keep[i]) continue;
    const bool last = i + 1 == rings;
    const int32_t a = first + i * width, b = first + (last ? 0 : i + 1) * width;
    for (int32_t j = 0; j < (closed_ring ? width : width - 1); ++j) {
      const int32_t j1 = (j + 1) % width;
      const int32_t bj = last ? (j + shift) % width : j, bj1 = last ? (j1 + shift) % width : j1;
      mesh.add_face({a + j, a + j1, b + bj1, b + bj});
    }
  }
}

// The surface normal at the control point of triangle i (of cycle c), weighted like the
// point itself: (2 apex + p + n) / 4.
Vec3 control_normal(const QuadMesh& quads, const TriangleCycle& cycle, const Ladder& ladder, int32_t c, size_t i) {
  const auto [p, apex, n] = cycle_triangle(quads, cycle.order[i]);
  const Vec3 sum = surface_normal(ladder, c, i, apex) * 2.0f + surface_normal(ladder, c, i, p) + surface_normal(ladder, c, i, n);
  return norm(sum) > 0 ? normalized(sum) : ladder.up[i];
}

// The swept section's frame at every point of the smooth curve: computed once, so that
// --radius auto can try several radii on it.
struct Sweep {
  Polylines centre;
  std::vector<Vec3> normal, binormal; // per point
  std::vector<uint8_t> mobius;        // per cycle
};

Sweep sweep_frames(const QuadMesh& quads, const TriangleCycle& cycle, const CurveOptions& curve) {
  Sweep sweep;
  sweep.centre = cycle_curves(quads, cycle, curve);
  const Ladder ladder = make_ladder(quads, cycle);
  sweep.mobius = ladder.mobius;
  sweep.normal.resize(sweep.centre.points.size());
  sweep.binormal.resize(sweep.centre.points.size());
  const int32_t k = curve.smoothing == Smoothing::none ? 1 : curve.samples;
  for (int32_t c = 0; c < sweep.centre.size(); ++c) {
    const auto points = sweep.centre.polyline(c);
    const int32_t m = int32_t(points.size()), first = sweep.centre.start[size_t(c)];
    const size_t first_triangle = size_t(cycle.cycle_start[size_t(c)]);
    const int32_t triangles = cycle.cycle_start[size_t(c) + 1] - cycle.cycle_start[size_t(c)];
    // The surface normal at each control point, weighted like the point itself.
    std::vector<Vec3> normal_at(static_cast<size_t>(triangles));
    for (int32_t t = 0; t < triangles; ++t) normal_at[size_t(t)] = control_normal(quads, cycle, ladder, c, first_triangle + size_t(t));
    auto up = [&](int32_t control) {
      const int32_t wrapped = (control % triangles + triangles) % triangles;
      const Vec3 u = normal_at[size_t(wrapped)];
      return ladder.mobius[size_t(c)] && wrapped != control ? u * -1.0f : u;
    };
    Vec3 tangent{}, normal{};
    for (int32_t i = 0; i < m; ++i) {
      const auto w = bspline_weights(float(i % k) / float(k));
      Vec3 blended{};
      for (int j = 0; j < 4; ++j) blended = blended + up(i / k - 1 + j) * w[size_t(j)];
      // A repeated point has no direction of its own: it keeps the previous frame.
      if (const Vec3 t = section_normal(points[size_t((i + m - 1) % m)], points[size_t(i)], points[size_t((i + 1) % m)]);
          norm(t) > 0)
        tangent = t;
      if (const Vec3 nrm = normalized(blended - tangent * float(dot(blended, tangent))); norm(nrm) > 0) normal = nrm;
      sweep.normal[size_t(first + i)] = normal;
      sweep.binormal[size_t(first + i)] = cross(tangent, normal);
    }
  }
  return sweep;
}

// The frames along given curves with the surface's normal at each point (constant_wire's
// second form): the normals made to agree along each curve and smoothed over a few
// points, then made perpendicular to the curve.
Sweep sweep_along(const Polylines& centre, std::span<const Vec3> normals) {
  Sweep sweep;
  sweep.centre = centre;
  sweep.normal.assign(normals.begin(), normals.end());
  sweep.binormal.resize(normals.size());
  sweep.mobius.assign(size_t(centre.size()), 0);
  std::vector<Vec3> smoothed(normals.size());
  for (int32_t c = 0; c < centre.size(); ++c) {
    const int32_t first = centre.start[size_t(c)], m = centre.start[size_t(c) + 1] - first;
    Vec3* up = sweep.normal.data() + first;
    for (int32_t i = 1; i < m; ++i)
      if (dot(up[i], up[i - 1]) < 0) up[i] = up[i] * -1.0f;
    const bool mobius = m > 1 && dot(up[m - 1], up[0]) < 0;
    sweep.mobius[size_t(c)] = mobius;
    // Across the closing point of a Möbius curve the normal turns over.
    auto at = [&](int32_t i) { return i < 0 ? (mobius ? up[i + m] * -1.0f : up[i + m]) : i >= m ? (mobius ? up[i - m] * -1.0f : up[i - m]) : up[i]; };
    for (int round = 0; round < 4; ++round) {
      for (int32_t i = 0; i < m; ++i) smoothed[size_t(i)] = at(i) * 0.5f + (at(i - 1) + at(i + 1)) * 0.25f;
      std::copy(smoothed.begin(), smoothed.begin() + m, up);
    }
    const auto points = centre.polyline(c);
    Vec3 tangent{}, normal{};
    for (int32_t i = 0; i < m; ++i) {
      if (const Vec3 t = section_normal(points[size_t((i + m - 1) % m)], points[size_t(i)], points[size_t((i + 1) % m)]);
          norm(t) > 0)
        tangent = t;
      Vec3 want = normalized(up[i] - tangent * float(dot(up[i], tangent)));
      // A section turned more than 60 degrees from the last one twists the tube between
      // them into itself (a segment straight across a thin part, along which the
      // surface's normal turns over): it turns half way toward the surface's normal.
      if (const Vec3 carried = normalized(normal - tangent * float(dot(normal, tangent)));
          i > 0 && norm(carried) > 0 && dot(want, carried) < 0.5f) {
        const Vec3 half = normalized(carried + want);
        want = norm(half) > 0 ? half : carried;
      }
      if (norm(want) > 0) normal = want;
      up[i] = normal;
      sweep.binormal[size_t(first + i)] = cross(tangent, normal);
    }
  }
  return sweep;
}

// The tube (wire) or band (ribbon) of `radius` around the sweep: every section's
// vertices, and the faces of the segments `keep` selects (all if it is empty).
PolygonMesh sweep_mesh(const Sweep& sweep, WireShape shape, int32_t sides, double radius, const std::vector<uint8_t>& keep = {}) {
  const bool ribbon = shape == WireShape::ribbon;
  // A ribbon is the sweep of a two-point section at +-90 degrees from the normal.
  const int32_t width = ribbon ? 2 : sides;
  std::vector<double> cos_a(static_cast<size_t>(width)), sin_a(static_cast<size_t>(width));
  for (int32_t j = 0; j < width; ++j) {
    const double angle = ribbon ? (j == 0 ? -0.5 : 0.5) * std::numbers::pi : 2 * std::numbers::pi * (j + 0.5) / width;
    cos_a[size_t(j)] = std::cos(angle);
    sin_a[size_t(j)] = std::sin(angle);
  }
  PolygonMesh mesh;
  const size_t points = sweep.centre.points.size();
  mesh.positions.resize(points * size_t(width));
  mesh.face_vertices.reserve(points * size_t(width) * 4);
  mesh.face_start.reserve(points * size_t(width) + 1);
  for (int32_t c = 0; c < sweep.centre.size(); ++c) {
    const int32_t first = sweep.centre.start[size_t(c)], m = sweep.centre.start[size_t(c) + 1] - first;
    // On a Moebius cycle the last section must land on the first turned by half a turn.
    // A polygon with an even number of sides maps onto itself that way; an odd one needs
    // an extra turn of -pi/sides, spread evenly along the loop so no segment twists.
    const int32_t shift = sweep.mobius[size_t(c)] ? width / 2 : 0;
    const double twist = sweep.mobius[size_t(c)] ? 2 * std::numbers::pi * shift / width - std::numbers::pi : 0.0;
    for (int32_t i = 0; i < m; ++i) {
      const size_t g = size_t(first + i);
      const double co = std::cos(twist * i / m), so = std::sin(twist * i / m);
      for (int32_t j = 0; j < width; ++j) {
        const double ca = cos_a[size_t(j)] * co - sin_a[size_t(j)] * so, sa = sin_a[size_t(j)] * co + cos_a[size_t(j)] * so;
        mesh.positions[g * size_t(width) + size_t(j)] =
            sweep.centre.points[g] + (sweep.normal[g] * float(ca) + sweep.binormal[g] * float(sa)) * float(radius);
      }
    }
    connect_rings(mesh, first * width, m, width, !ribbon, shift, keep.empty() ? nullptr : keep.data() + first);
  }
  return mesh;
}

} // namespace


namespace {

// The analytic clearance of a tube around closed polylines: the radius, and per point
// the smallest radius at which anything there may run into the tube, so that a check
// of larger radii can look only where it matters. Pairs of segments are searched up to
// `reach` times the local bounds. Without `bends`, only the parts that come back near
// each other count, not the curvature (for slabs, whose thickness is across the curve's
// plane rather than around it), and only the local bounds are computed (`radius` is
// left at the search limit).
struct Clearance {
  double radius = 0;
  std::vector<double> local;
};

Clearance tube_clearance(const Polylines& centre, int samples_per_segment, double reach, bool bends = true) {
  const size_t n = centre.points.size();
  Clearance out;
  out.local.assign(n, INFINITY);
  if (n < 3) return out;
  // Per segment: its curve, its length, and the arc length at its start.
  std::vector<int32_t> curve_of(n);
  std::vector<double> length(n), arc(n);
  std::vector<double> total(size_t(centre.size()));
  double sum_length = 0;
  for (int32_t c = 0; c < centre.size(); ++c) {
    const auto pts = centre.polyline(c);
    double s = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
      const size_t g = size_t(centre.start[size_t(c)]) + i;
      curve_of[g] = c;
      arc[g] = s;
      length[g] = norm(pts[(i + 1) % pts.size()] - pts[i]);
      s += length[g];
    }
    total[size_t(c)] = s;
    sum_length += s;
  }
  auto next = [&](size_t g) {
    const int32_t c = curve_of[g];
    return g + 1 == size_t(centre.start[size_t(c) + 1]) ? size_t(centre.start[size_t(c)]) : g + 1;
  };
  auto prev = [&](size_t g) {
    const int32_t c = curve_of[g];
    return g == size_t(centre.start[size_t(c)]) ? size_t(centre.start[size_t(c) + 1]) - 1 : g - 1;
  };

  // A wider tube folds where the curve bends: its radius must stay below the radius of
  // curvature, taken as that of the circle through each point and its two neighbours.
  // And the tube's pieces on either side of a section must stay on their own side of it:
  // the section at each end of a segment, tilted by the angle between the two sections,
  // reaches r sin(angle) across the other, which must be less than the segment's extent
  // along the other's normal. On a hairpin that extent is tiny or even negative.
  double limit = 2.0 * std::max(1, samples_per_segment) * sum_length / double(n);
  auto section = [&](size_t g) { return section_normal(centre.points[prev(g)], centre.points[g], centre.points[next(g)]); };
  for (size_t g = 0; g < n && bends; ++g) {
    const Vec3 a = centre.points[prev(g)], b = centre.points[g], c = centre.points[next(g)];
    const double twice_area = norm(cross(b - a, c - a));
    if (twice_area > 0) out.local[g] = std::min(out.local[g], norm(b - a) * norm(c - b) * norm(c - a) / (2 * twice_area));
    if (length[g] == 0) continue;
    const Vec3 t0 = section(g), t1 = section(next(g)), step = c - b;
    const double tilt = norm(cross(t0, t1));
    if (tilt > 0) {
      const double bound = std::max(0.0, std::min(dot(step, t0), dot(step, t1))) / tilt;
      out.local[g] = std::min(out.local[g], bound);
      out.local[next(g)] = std::min(out.local[next(g)], bound);
    }
  }
  for (double bound : out.local) limit = std::min(limit, bound);
  if (!(limit > 0)) return out;

  // Parts of the curve that come back near each other: every pair of segments closer
  // than 2 * limit (times `reach`) is found with a uniform grid. A pair at distance d
  // forbids the radii in (d/2, arc/pi): up to d/2 the tubes stay apart, and from arc/pi
  // the pair lies within one bend of the tube, which the folding bound already covers.
  // Each segment is entered in the cells its box meets grown by half that distance, so
  // that two segments closer than it share the cell of the midpoint between their
  // nearest points: only pairs within a cell are looked at. Cells no smaller than the
  // mean segment, so that a long segment spans few of them, and few enough per axis that
  // a cell's number fits 63 bits.
  const Box3 box = bounding_box(centre.points);
  const double extent = std::max({box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z});
  const double cell = std::max({2 * limit * reach, sum_length / double(n), extent / double(1 << 20)});
  // Far above the float rounding of segment_distance, so that a pair it puts within
  // reach is found however close to the edge.
  const double slack = 1e-6 * std::max({std::abs(box.min.x), std::abs(box.min.y), std::abs(box.min.z), std::abs(box.max.x),
                                        std::abs(box.max.y), std::abs(box.max.z)});
  const double grow = limit * reach + slack;
  auto cell_of = [&](double v, double lo) { return int64_t(std::floor((v - lo) / cell)); };
  const int64_t nx = cell_of(box.max.x, box.min.x) + 1, ny = cell_of(box.max.y, box.min.y) + 1,
                nz = cell_of(box.max.z, box.min.z) + 1;
  auto key = [&](int64_t x, int64_t y, int64_t z) { return (z * ny + y) * nx + x; };
  // The cells [first, last] that coordinates in [lo - grow, hi + grow] meet, within the box.
  auto cells_of = [&](float a, float b, float lo, int64_t count) {
    return std::pair{std::max<int64_t>(0, cell_of(std::min(a, b) - grow, lo)),
                     std::min(count - 1, cell_of(std::max(a, b) + grow, lo))};
  };
  std::vector<std::pair<int64_t, int32_t>> entries;
  entries.reserve(n);
  for (size_t g = 0; g < n; ++g) {
    const Vec3 a = centre.points[g], b = centre.points[next(g)];
    const auto [x0, x1] = cells_of(a.x, b.x, box.min.x, nx);
    const auto [y0, y1] = cells_of(a.y, b.y, box.min.y, ny);
    const auto [z0, z1] = cells_of(a.z, b.z, box.min.z, nz);
    for (int64_t z = z0; z <= z1; ++z)
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t x = x0; x <= x1; ++x) entries.push_back({key(x, y, z), int32_t(g)});
  }
  std::sort(entries.begin(), entries.end());
  std::vector<std::pair<double, double>> forbidden; // (d/2, arc/pi)
  // Segments apart by more than the reach along one axis are apart: that test spares
  // segment_distance for most pairs a cell brings (cells are mostly far larger than the
  // reach), and its slack keeps exactly the pairs segment_distance would keep.
  auto apart = [&](Vec3 a0, Vec3 a1, Vec3 b0, Vec3 b1, double gap) {
    auto axis = [&](float a, float b, float c, float d) {
      return double(std::min(c, d)) - std::max(a, b) > gap || double(std::min(a, b)) - std::max(c, d) > gap;
    };
    return axis(a0.x, a1.x, b0.x, b1.x) || axis(a0.y, a1.y, b0.y, b1.y) || axis(a0.z, a1.z, b0.z, b1.z);
  };
  auto consider = [&](size_t g, size_t h) {
    if (g == h || next(g) == h || next(h) == g) return;
    const Vec3 g0 = centre.points[g], g1 = centre.points[next(g)], h0 = centre.points[h], h1 = centre.points[next(h)];
    if (apart(g0, g1, h0, h1, 2 * limit * reach + slack)) return;
    const double d = segment_distance(g0, g1, h0, h1);
    if (d >= 2 * limit * reach) return;
    double between = INFINITY;
    if (curve_of[g] == curve_of[h]) {
      const size_t lo = std::min(g, h), hi = std::max(g, h);
      const double inner = arc[hi] - arc[lo] - length[lo];
      between = std::min(inner, total[size_t(curve_of[g])] - inner - length[lo] - length[hi]);
    }
    if (between / std::numbers::pi > d / 2) {
      if (d / 2 < limit && bends) forbidden.push_back({d / 2, between / std::numbers::pi});
      out.local[g] = std::min(out.local[g], d / 2);
      out.local[h] = std::min(out.local[h], d / 2);
    }
  };
  for (size_t e = 0; e < entries.size();) {
    size_t end = e;
    while (end < entries.size() && entries[end].first == entries[e].first) ++end;
    for (size_t i = e; i < end; ++i)
      for (size_t j = i + 1; j < end; ++j) consider(size_t(entries[i].second), size_t(entries[j].second));
    e = end;
  }
  // The largest radius up to `limit` that no pair forbids: sweep the intervals by
  // decreasing lower end, dropping to the lower end of each one that covers the radius.
  std::sort(forbidden.begin(), forbidden.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  out.radius = limit;
  for (const auto& [lo, hi] : forbidden)
    if (lo < out.radius && out.radius < hi) out.radius = lo;
  return out;
}

} // namespace

double max_wire_radius(const Polylines& centre, int samples_per_segment) {
  return tube_clearance(centre, samples_per_segment, 1.0).radius;
}

namespace {

int32_t samples_per_segment(const CurveOptions& curve) { return curve.smoothing == Smoothing::none ? 1 : curve.samples; }

// auto_wire_radius on a sweep whose curve has about k points per segment of its control
// polygon (or per spacing).
double auto_radius(const Sweep& sweep, const ConstantWireOptions& options, int32_t k) {
  constexpr double step = 1.1, reach = 1.35; // reach >= step^steps
  constexpr int steps = 3;
  const Clearance clearance = tube_clearance(sweep.centre, k, reach);
  double radius = clearance.radius;
  if (!(radius > 0)) return 0;
  // Only the pieces of tube within two points of a spot whose bound is below the largest
  // radius tried can collide; the check looks at those pieces alone.
  std::vector<uint8_t> near(sweep.centre.points.size());
  for (int32_t c = 0; c < sweep.centre.size(); ++c) {
    const int32_t first = sweep.centre.start[size_t(c)], m = sweep.centre.start[size_t(c) + 1] - first;
    for (int32_t i = 0; i < m; ++i)
      if (clearance.local[size_t(first + i)] < radius * reach)
        for (int32_t j = -2; j <= 2; ++j) near[size_t(first + ((i + j) % m + m) % m)] = 1;
  }
  for (int s = 0; s < steps; ++s) {
    const PolygonMesh pieces = sweep_mesh(sweep, options.shape, options.sides, radius * step, near);
    if (check_printability(pieces, {.thickness = false}).self_intersecting) break;
    radius *= step;
  }
  return radius;
}

} // namespace

double auto_wire_radius(const QuadMesh& quads, const TriangleCycle& cycle, const ConstantWireOptions& options) {
  return auto_radius(sweep_frames(quads, cycle, options.curve), options, samples_per_segment(options.curve));
}

int64_t constant_wire_triangles(int64_t cycle_triangles, const ConstantWireOptions& options) {
  const int64_t points = cycle_triangles * (options.curve.smoothing == Smoothing::none ? 1 : options.curve.samples);
  // Two triangles per quad: `sides` quads per curve point around a wire, one across a ribbon.
  return points * 2 * (options.shape == WireShape::wire ? options.sides : 1);
}

int64_t variable_wire_triangles(int64_t cycle_triangles, const VariableWireOptions& options) {
  // Per rung 4 control quads (wire) or 1 (ribbon), 4 each per level.
  const double triangles =
      double(cycle_triangles) * options.rungs * (options.shape == WireShape::wire ? 8 : 2) * std::pow(4.0, options.levels);
  return triangles < 0x1p62 ? int64_t(triangles) : int64_t(1) << 62;
}

namespace {

// How far a slab's normal may lean from its triangle's. Across a sharp crease the vertex
// normals average the faces on either side, and a triangle on a steep side can have a
// rung lying along them: the slab's section, that rung swept along the normal, then has
// no width and its walls cross (the cut of a scan's neck, which every seed crossed). At
// 45 degrees the section keeps at least sin 45 of its area; 60 left crossings there.
constexpr double max_slab_tilt = std::numbers::pi / 4;

// `v` (unit) turned towards the unit `axis` until it is within `angle` of it.
Vec3 within_cone(Vec3 v, Vec3 axis, double angle) {
  const double cosine = dot(v, axis);
  const Vec3 aside = v - axis * float(cosine);
  if (cosine >= std::cos(angle)) return v;
  if (norm(aside) == 0) return axis;
  return normalized(axis * float(std::cos(angle)) + normalized(aside) * float(std::sin(angle)));
}

// Refuses a result a mesh cannot index, before any of it is made.
void require_indexable(int64_t triangles, const std::string& what) {
  if (triangles > 2147483647)
    throw UsageError(what + " would have " + std::to_string(triangles) + " triangles, more than a mesh can index (2^31 - 1)");
}

void check_constant_options(const ConstantWireOptions& options) {
  if (options.radius && (!(*options.radius > 0) || !std::isfinite(*options.radius)))
    throw ParameterError("radius", " must be a positive number (got " + std::to_string(*options.radius) + ")");
  if (options.shape == WireShape::wire && options.sides < 3)
    throw ParameterError("sides", " must be at least 3 (got " + std::to_string(options.sides) + ")");
}

} // namespace

ConstantWire constant_wire(const QuadMesh& quads, const TriangleCycle& cycle, const ConstantWireOptions& options) {
  check_constant_options(options);
  require_indexable(constant_wire_triangles(cycle.num_triangles(), options),
                    options.shape == WireShape::wire
                        ? "the wire of " + std::to_string(options.sides) + " sides at " + std::to_string(options.curve.samples) + " samples a segment"
                        : "the ribbon at " + std::to_string(options.curve.samples) + " samples a segment");
  const Sweep sweep = sweep_frames(quads, cycle, options.curve);
  const double radius = options.radius ? *options.radius : auto_radius(sweep, options, samples_per_segment(options.curve));
  if (!(radius > 0)) return {};
  return {sweep_mesh(sweep, options.shape, options.sides, radius), radius};
}

ConstantWire constant_wire(const Polylines& centre, std::span<const Vec3> normals, const ConstantWireOptions& options) {
  check_constant_options(options);
  if (normals.size() != centre.points.size())
    throw ParameterError("normals", ": expected one per curve point (" + std::to_string(centre.points.size()) + "), got " +
                                        std::to_string(normals.size()));
  require_indexable(int64_t(centre.points.size()) * 2 * (options.shape == WireShape::wire ? options.sides : 1),
                    "the " + std::string(options.shape == WireShape::wire ? "wire" : "ribbon"));
  const Sweep sweep = sweep_along(centre, normals);
  // relax_curves puts about 4 points in a spacing, which is what the clearance search
  // takes for a segment of the control polygon.
  const double radius = options.radius ? *options.radius : auto_radius(sweep, options, 4);
  if (!(radius > 0)) return {};
  return {sweep_mesh(sweep, options.shape, options.sides, radius), radius};
}

namespace {

// The quads of a smoothed wire are not flat, and where two parts of it pass close, which
// diagonal splits them decides whether they touch. Each quad is split here, along the
// diagonal whose triangles' area normals agree best (as CGAL's triangulate_faces does),
// so that every writer, our check and a slicer see the same, better, triangles instead
// of each fanning from the first corner.
// `mesh` gives the faces, `positions` their corners' places.
PolygonMesh split_quads(const PolygonMesh& mesh, std::vector<Vec3> positions) {
  PolygonMesh out;
  out.positions = std::move(positions);
  out.face_vertices.reserve(size_t(mesh.num_faces()) * 6);
  out.face_start.reserve(size_t(mesh.num_faces()) * 2 + 1);
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> v = mesh.face(f);
    if (v.size() != 4) {
      out.add_face(v);
      continue;
    }
    const auto p = [&](int k) { return out.positions[size_t(v[size_t(k)])]; };
    const double along_02 = dot(cross(p(1) - p(0), p(2) - p(0)), cross(p(2) - p(0), p(3) - p(0)));
    const double along_13 = dot(cross(p(2) - p(1), p(3) - p(1)), cross(p(3) - p(1), p(0) - p(1)));
    if (along_02 >= along_13) {
      out.add_face({v[0], v[1], v[2]});
      out.add_face({v[0], v[2], v[3]});
    } else {
      out.add_face({v[1], v[2], v[3]});
      out.add_face({v[1], v[3], v[0]});
    }
  }
  return out;
}

// Refuses options out of range and a result a mesh cannot index, before any work.
void check_variable_options(const TriangleCycle& cycle, const VariableWireOptions& options) {
  for (const auto& [name, value] : {std::pair{"s", options.s}, {"t", options.t}})
    if (!(value >= 0 && value <= 1)) throw ParameterError(name, " must be between 0 and 1 (got " + std::to_string(value) + ")");
  if (!(options.thickness >= 0) || !std::isfinite(options.thickness))
    throw ParameterError("thickness", " must be 0 (automatic) or a positive number (got " + std::to_string(options.thickness) + ")");
  if (options.levels < 0) throw ParameterError("levels", " must be >= 0 (got " + std::to_string(options.levels) + ")");
  if (options.rungs != 1 && options.rungs != 2) throw ParameterError("rungs", " must be 1 or 2 (got " + std::to_string(options.rungs) + ")");
  require_indexable(variable_wire_triangles(cycle.num_triangles(), options),
                    "the variable " + std::string(options.shape == WireShape::wire ? "wire" : "ribbon") + " at " +
                        std::to_string(options.levels) + " levels");
}

// The rungs of the strip, `per` triangle of the cycle (VariableWireOptions::rungs: where
// the curve enters its trapezoid and where it leaves, or its middle), each with the
// normal its slab stands on. Triangle i's rungs are per * i onwards.
struct Rungs {
  std::vector<Vec3> left, right, up;
  int per = 2;
  size_t size() const { return left.size(); }
};

// The paper's trapezoid in each triangle of the cycle, as its two rungs. The bilinear
// formula with p00 = p01 = apex, p10 = n, p11 = p keeps the triangle's rotation order;
// corner v_mn is p_(1-m)(1-n) when s = t = 1.
Rungs trapezoid_rungs(const QuadMesh& quads, const TriangleCycle& cycle, const Ladder& ladder, const VariableWireOptions& options) {
  const int per = options.rungs;
  const size_t size = size_t(per) * cycle.order.size();
  Rungs rungs{std::vector<Vec3>(size), std::vector<Vec3>(size), std::vector<Vec3>(size), per};
  const double t = per == 1 ? 0 : options.t; // one rung: the middle, where both ends meet at t = 0
  const float w0s = float((1 - options.s) / 2), w1s = float((1 + options.s) / 2);
  const float w0t = float((1 - t) / 2), w1t = float((1 + t) / 2);
  // Corners on the p side, then the n side, each as (apex rail, other rail).
  auto trapezoid = [&](Vec3 p, Vec3 a, Vec3 q) {
    return std::array<std::pair<Vec3, Vec3>, 2>{{{a * w1s + (q * w0t + p * w1t) * w0s, a * w0s + (q * w0t + p * w1t) * w1s},
                                                 {a * w1s + (p * w0t + q * w1t) * w0s, a * w0s + (p * w0t + q * w1t) * w1s}}};
  };
  for (int32_t c = 0; c < cycle.num_cycles(); ++c) {
    const size_t first = size_t(cycle.cycle_start[size_t(c)]), count = size_t(cycle.cycle_start[size_t(c) + 1]) - first;
    for (size_t k = 0; k < count; ++k) {
      const size_t i = first + k;
      const auto [pi, ai, ni] = cycle_triangle(quads, cycle.order[i]);
      const auto corners = trapezoid(quads.positions[size_t(pi)], quads.positions[size_t(ai)], quads.positions[size_t(ni)]);
      // One normal for the whole trapezoid, so that its slab is a right prism: where a
      // thin triangle turns the curve round (an apex angle near 180 degrees) the slab is
      // a plate as thin as the triangle, and any difference between the normals of its
      // corners tilts its walls into each other. Smooth (vertex) normals on a coherent
      // cycle, within max_slab_tilt of the triangle's own; otherwise the ladder's up side.
      const Vec3 normal = ladder.coherent[size_t(c)] ? within_cone(control_normal(quads, cycle, ladder, c, i), ladder.up[i], max_slab_tilt)
                                                     : ladder.up[i];
      const bool entry_p = ladder.entry_is_p[i], apex_right = ladder.apex_right[i];
      for (size_t r = 0; r < size_t(per); ++r) {
        const size_t side = r == 0 ? !entry_p : entry_p, rung = size_t(per) * i + r;
        const auto [apex_corner, other_corner] = corners[side];
        rungs.left[rung] = apex_right ? other_corner : apex_corner;
        rungs.right[rung] = apex_right ? apex_corner : other_corner;
        rungs.up[rung] = normal;
      }
    }
  }
  return rungs;
}

// The largest half thickness per rung of a wire of automatic thickness. The automatic
// thickness follows the ribbon's local width, as the width follows the triangles: one
// global figure makes tall walls of the narrow parts, whose tops meet in hollows and
// fold over in tight turns.
//
// Where the slabs of two consecutive triangles meet at an angle, the sections at the
// two ends of their connector lean towards each other on the inside of the bend and
// cross at L / (2 tan(angle / 2)) from it (L: the connector's length): a thicker slab
// folds into itself there (the tetrahedron's edges, a hexahedral mesh's creases). The
// automatic thickness stays below that, with a margin for the smoothing, and below the
// triangle's smallest altitude: a slab taller than its triangle is wide (a sliver of a
// CAD model's fans, a scan's needles) leans into its neighbours wherever the surface
// curves.
std::vector<float> thickness_limits(const QuadMesh& quads, const TriangleCycle& cycle, const Ladder& ladder, const Rungs& rungs) {
  const std::vector<Vec3>& left = rungs.left;
  const std::vector<Vec3>& right = rungs.right;
  const std::vector<Vec3>& up = rungs.up;
  const size_t per = size_t(rungs.per);
  std::vector<float> thickness_limit(rungs.size());
  for (size_t i = 0; i < thickness_limit.size() / per; ++i) {
    const auto [pi, ai, ni] = cycle_triangle(quads, cycle.order[i]);
    const Vec3 p = quads.positions[size_t(pi)], a = quads.positions[size_t(ai)], q = quads.positions[size_t(ni)];
    const double longest = std::max({norm(a - p), norm(q - a), norm(p - q)});
    std::fill_n(thickness_limit.begin() + int64_t(per * i), per, float(longest > 0 ? 0.5 * norm(cross(a - p, q - p)) / longest : 0.0));
  }
  for (int32_t c = 0; c < cycle.num_cycles(); ++c) {
    const size_t first = per * size_t(cycle.cycle_start[size_t(c)]), count = per * size_t(cycle.cycle_start[size_t(c) + 1]) - first;
    for (size_t k = per - 1; k < count; k += per) { // each connector: a triangle's last rung to the next one's first
      const size_t a = first + k, b = first + (k + 1) % count;
      const bool swap = (k + 1) % count == 0 && ladder.mobius[size_t(c)]; // left meets right
      const double angle = std::acos(std::clamp(double(dot(up[a], up[b])) * (swap ? -1 : 1), -1.0, 1.0));
      const double length = swap ? std::min(norm(left[b] - right[a]), norm(right[b] - left[a]))
                                 : std::min(norm(left[b] - left[a]), norm(right[b] - right[a]));
      if (angle > 1e-6) thickness_limit[a] = thickness_limit[b] = std::min({thickness_limit[a], thickness_limit[b], float(0.7 * length / (2 * std::tan(angle / 2)))});
    }
  }
  // And the slabs of passes that come back near each other (the two sides of a thin
  // leg or plate) must not reach each other: each stays below 0.7 times half the distance
  // from its rung's midpoint to any other part of the strip's midline, found as the
  // constant wire's clearance is, on a grid, without its bends.
  Polylines midline;
  midline.points.resize(left.size());
  for (size_t r = 0; r < left.size(); ++r) midline.points[r] = (left[r] + right[r]) * 0.5f;
  midline.start.resize(cycle.cycle_start.size());
  for (size_t c = 0; c < cycle.cycle_start.size(); ++c) midline.start[c] = rungs.per * cycle.cycle_start[c];
  const Clearance apart = tube_clearance(midline, 1, 1.0, false);
  for (size_t r = 0; r < left.size(); ++r) thickness_limit[r] = std::min(thickness_limit[r], float(0.7 * apart.local[r]));
  return thickness_limit;
}

// The sections of the control mesh: a ribbon's rung (left, right); a wire's slab (left
// below, left above, right above, right below), which makes the faces point out of the
// slab. The clearing rounds (clear_crossings) scale them per rung: `thinned` the
// thickness, `narrowed` the width about the rung's midpoint.
struct Sections {
  const Rungs& rungs;
  bool ribbon, automatic, clearing;
  double thickness;              // VariableWireOptions::thickness
  std::vector<float> limit;      // thickness_limits, for an automatic thickness
  std::vector<float> thinned;    // per rung, when clearing
  std::vector<float> narrowed;   // per rung, when clearing

  int32_t width() const { return ribbon ? 2 : 4; }

  float half_thickness(size_t rung) const {
    if (!automatic) return float(thickness / 2);
    return std::min(limit[rung], float(0.25 * norm(rungs.right[rung] - rungs.left[rung])));
  }

  // The control mesh's positions, width() per rung.
  std::vector<Vec3> positions() const {
    const std::vector<Vec3>& left = rungs.left;
  const std::vector<Vec3>& right = rungs.right;
  const std::vector<Vec3>& up = rungs.up;
    std::vector<Vec3> out;
    out.reserve(left.size() * size_t(width()));
    for (size_t r = 0; r < left.size(); ++r) {
      const float n = clearing ? narrowed[r] : 1.0f;
      const Vec3 mid = (left[r] + right[r]) * 0.5f, l = mid + (left[r] - mid) * n, rr = mid + (right[r] - mid) * n;
      if (ribbon) {
        out.insert(out.end(), {l, rr});
      } else {
        const Vec3 h = up[r] * (half_thickness(r) * (clearing ? thinned[r] : 1.0f));
        out.insert(out.end(), {l - h, l + h, rr + h, rr - h});
      }
    }
    return out;
  }
};

// The sections joined into one closed ring of quads per cycle.
PolygonMesh control_mesh(const Sections& sections, const TriangleCycle& cycle, const Ladder& ladder) {
  PolygonMesh control;
  control.positions = sections.positions();
  const int32_t width = sections.width();
  for (int32_t c = 0; c < cycle.num_cycles(); ++c) {
    const int32_t per = sections.rungs.per;
    const int32_t first = per * cycle.cycle_start[size_t(c)], rungs = per * cycle.cycle_start[size_t(c) + 1] - first;
    // Where a Moebius cycle closes, left meets right: a ribbon's rung is reversed, a
    // slab turned by half a turn (both directions swap).
    connect_rings(control, first * width, rungs, width, !sections.ribbon, ladder.mobius[size_t(c)] ? width / 2 : 0);
  }
  return control;
}

// The wire from its control mesh: Catmull-Clark to the limit surface, its quads split.
// Level 0 is the control mesh itself; OpenSubdiv would build its whole topology (the
// better part of the time at 50k faces) only to copy it. `topology`, once the clearing
// rounds keep it (only then: it is large), is the control mesh's refined topology.
PolygonMesh smoothed(const PolygonMesh& control, const SubdivideOptions& options, const std::optional<CatmullClark>& topology) {
  if (options.levels == 0) return split_quads(control, control.positions);
  PolygonMesh smooth = topology ? topology->refine(control.positions) : subdivide(control, options);
  return split_quads(smooth, std::move(smooth.positions));
}

// The limits above are local estimates, and the smoothing moves what they measured.
// An automatic thickness is then made good where the result still crosses itself:
// around each crossing the slabs are halved (and from the second time on, narrowed
// about their middle: where the strip bends across a sharp crease its sides fold
// however thin it is), the wire smoothed again and searched again where it changed,
// for a few rounds. A ribbon, which has no thickness, is narrowed from the first
// round: smoothing pulls the strips of neighbouring passes into each other at creases.
// What does not clear is reported as it is: mostly a surface that crosses itself, or
// slivers so flat that their slab folds in its own plane. Every control quad of a
// connector (a wire's ring has 4, a ribbon's 1) refines into 4^levels quads
// (OpenSubdiv numbers a face's children consecutively), each split in 2 triangles.
// Updates `wire`, `control` and `sections`; returns whether the last search found the
// wire clear.
bool clear_crossings(PolygonMesh& wire, PolygonMesh& control, Sections& sections, const TriangleCycle& cycle,
                     const SubdivideOptions& smoothing, Progress* progress) {
  const bool ribbon = sections.ribbon;
  std::vector<float>& thinned = sections.thinned;
  std::vector<float>& narrowed = sections.narrowed;
  std::optional<CatmullClark> topology;
  const int64_t faces_per_rung = int64_t(ribbon ? 1 : sections.width()) * 2 << (2 * smoothing.levels);
  const int64_t per = sections.rungs.per;
  auto step = [&](size_t rung, int delta) {
    const auto c = size_t(std::upper_bound(cycle.cycle_start.begin(), cycle.cycle_start.end(), int32_t(int64_t(rung) / per)) -
                          cycle.cycle_start.begin() - 1);
    const int64_t first = per * int64_t(cycle.cycle_start[c]), rungs = per * int64_t(cycle.cycle_start[c + 1]) - first;
    return size_t(first + ((int64_t(rung) - first + delta) % rungs + rungs) % rungs);
  };
  std::vector<uint8_t> changed; // per face of the wire: empty = search it all
  size_t fewest = SIZE_MAX; // crossing faces, and the rounds since they were a tenth fewer
  for (int round = 0, stalled = 0; round < 8 && stalled < 2; ++round) {
    check_progress(progress);
    const std::vector<int32_t> crossing = self_intersecting_faces(wire, changed, progress);
    if (crossing.empty()) return true;
    stalled = double(crossing.size()) < 0.9 * double(fewest) ? 0 : stalled + 1;
    fewest = std::min(fewest, crossing.size());
    // A connector's limit surface depends on its own two rungs and their neighbours.
    std::vector<uint8_t> thin(thinned.size());
    for (const int32_t f : crossing) {
      const size_t rung = size_t(f / faces_per_rung);
      for (int d = -1; d <= 2; ++d) thin[step(rung, d)] = 1;
    }
    // A rung halved four times and still crossing is given up (a crossing surface or a
    // flat sliver, which no thickness clears): the rounds end when only those are left.
    changed.assign(size_t(wire.num_faces()), 0);
    bool any = false;
    for (size_t r = 0; r < thinned.size(); ++r) {
      if (!thin[r] || thinned[r] < 0.1f) continue;
      any = true;
      if (thinned[r] < 1 || ribbon) narrowed[r] *= 0.7f;
      thinned[r] *= 0.5f;
      for (int d = -2; d <= 2; ++d) {
        const auto first = changed.begin() + int64_t(step(r, d)) * faces_per_rung;
        std::fill(first, first + faces_per_rung, uint8_t(1));
      }
    }
    if (!any) break;
    control.positions = sections.positions();
    if (!topology && smoothing.levels > 0) topology.emplace(control, smoothing);
    wire = smoothed(control, smoothing, topology);
  }
  return false;
}

} // namespace

VariableWire variable_wire(const QuadMesh& quads, const TriangleCycle& cycle, const VariableWireOptions& options,
                           Progress* progress) {
  check_variable_options(cycle, options);
  const bool ribbon = options.shape == WireShape::ribbon;
  const Ladder ladder = make_ladder(quads, cycle);
  const Rungs rungs = trapezoid_rungs(quads, cycle, ladder, options);
  // Only a wire of automatic thickness has limits. A ribbon of s or t = 1 covers the
  // surface by design, its trapezoids meeting along the triangles' sides: that is not to
  // be narrowed away.
  const bool automatic = !ribbon && options.thickness == 0;
  const bool clearing = options.clear && (automatic || (ribbon && options.s < 1 && options.t < 1));
  Sections sections{.rungs = rungs,
                    .ribbon = ribbon,
                    .automatic = automatic,
                    .clearing = clearing,
                    .thickness = options.thickness,
                    .limit = automatic ? thickness_limits(quads, cycle, ladder, rungs) : std::vector<float>(),
                    .thinned = std::vector<float>(clearing ? rungs.size() : 0, 1.0f),
                    .narrowed = std::vector<float>(clearing ? rungs.size() : 0, 1.0f)};
  PolygonMesh control = control_mesh(sections, cycle, ladder);
  const SubdivideOptions smoothing{.levels = options.levels, .limit = true};
  PolygonMesh wire = smoothed(control, smoothing, std::nullopt);
  const bool clear = clearing && clear_crossings(wire, control, sections, cycle, smoothing, progress);
  return {std::move(wire), clear};
}

std::vector<int32_t> crossing_cycle_triangles(const QuadMesh& quads, const TriangleCycle& cycle) {
  return self_intersecting_faces(cycle_triangles(quads, cycle));
}

} // namespace meander
