#include "meander/shell.h"

#include "meander/error.h"
#include "meander/printability.h"
#include "sculpture/sampled_shell.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace meander {
namespace {

using Triangle = std::array<int32_t, 3>;

// The two regions as one triangle surface, the points they share welded, each triangle
// with its region and quad.
struct Surface {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<uint8_t> region;
  std::vector<int32_t> quad;
  std::vector<int32_t> welded; // each vertex of region 0, then of region 1: its vertex here
};

// Where the vertices of regions laid out as `s.welded` says are (the regions' insides).
std::vector<Vec3> welded_positions(const Surface& s, const std::array<PolygonMesh, 2>& regions) {
  std::vector<Vec3> out(s.positions.size());
  size_t i = 0;
  for (const PolygonMesh& m : regions)
    for (const Vec3 p : m.positions) out[size_t(s.welded[i++])] = p;
  return out;
}

Surface weld(const std::array<PolygonMesh, 2>& regions, const RegionOrigins& origins) {
  std::vector<int64_t> points;
  for (int r = 0; r < 2; ++r)
    points.insert(points.end(), origins.vertex_point[size_t(r)].begin(), origins.vertex_point[size_t(r)].end());
  std::vector<int64_t> distinct = points;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  Surface s;
  s.positions.resize(distinct.size());
  s.welded.resize(points.size());
  size_t i = 0;
  for (int r = 0; r < 2; ++r)
    for (const Vec3 p : regions[size_t(r)].positions) {
      s.welded[i] = int32_t(std::lower_bound(distinct.begin(), distinct.end(), points[i]) - distinct.begin());
      s.positions[size_t(s.welded[i++])] = p;
    }
  int32_t offset = 0;
  for (int r = 0; r < 2; ++r) {
    const PolygonMesh& m = regions[size_t(r)];
    for (int32_t f = 0; f < m.num_faces(); ++f) {
      const std::span<const int32_t> v = m.face(f);
      for (size_t k = 1; k + 1 < v.size(); ++k) {
        s.triangles.push_back({s.welded[size_t(offset + v[0])], s.welded[size_t(offset + v[k])], s.welded[size_t(offset + v[k + 1])]});
        s.region.push_back(uint8_t(r));
        s.quad.push_back(origins.face_quad[size_t(r)][size_t(f)]);
      }
    }
    offset += m.num_vertices();
  }
  return s;
}

// A triangle side, as the surface's edges list it: sorted by its two vertices.
struct Side {
  int32_t low, high, face;
  bool forward; // the face goes low -> high
};

// The sides sorted so that those of one edge are adjacent. Throws TopologyError for an
// edge of more than two faces.
std::vector<Side> sides_of(const Surface& s) {
  std::vector<Side> sides;
  sides.reserve(3 * s.triangles.size());
  for (int32_t f = 0; f < int32_t(s.triangles.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = s.triangles[size_t(f)][size_t(k)], b = s.triangles[size_t(f)][size_t((k + 1) % 3)];
      sides.push_back({std::min(a, b), std::max(a, b), f, a < b});
    }
  std::sort(sides.begin(), sides.end(),
            [](const Side& x, const Side& y) { return std::tie(x.low, x.high, x.face) < std::tie(y.low, y.high, y.face); });
  for (size_t i = 0; i + 2 < sides.size(); ++i)
    if (sides[i].low == sides[i + 2].low && sides[i].high == sides[i + 2].high)
      throw TopologyError("the surface is not a 2-manifold: the edge from " + place(s.positions[size_t(sides[i].low)]) +
                          " to " + place(s.positions[size_t(sides[i].high)]) + " has more than two faces");
  return sides;
}

bool same_edge(const Side& x, const Side& y) { return x.low == y.low && x.high == y.high; }

// Turns the faces so that each component is consistently oriented, a closed one outward
// (positive volume), an open one as its first face was. Throws TopologyError for a
// non-orientable component.
void orient(Surface& s, const std::vector<Side>& sides) {
  const size_t nf = s.triangles.size();
  // Neighbours across each edge of two faces, and whether the two go the same way along it.
  std::vector<int32_t> start(nf + 1, 0);
  for (size_t i = 0; i + 1 < sides.size(); ++i)
    if (same_edge(sides[i], sides[i + 1])) {
      ++start[size_t(sides[i].face) + 1];
      ++start[size_t(sides[i + 1].face) + 1];
    }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::pair<int32_t, bool>> next(size_t(start.back()));
  std::vector<int32_t> fill(start.begin(), start.end() - 1);
  std::vector<uint8_t> open_face(nf, 0);
  for (size_t i = 0; i < sides.size(); ++i) {
    const bool paired_before = i > 0 && same_edge(sides[i - 1], sides[i]);
    const bool paired_after = i + 1 < sides.size() && same_edge(sides[i], sides[i + 1]);
    if (!paired_before && !paired_after) open_face[size_t(sides[i].face)] = 1;
    if (!paired_after) continue;
    const bool same = sides[i].forward == sides[i + 1].forward;
    next[size_t(fill[size_t(sides[i].face)]++)] = {sides[i + 1].face, same};
    next[size_t(fill[size_t(sides[i + 1].face)]++)] = {sides[i].face, same};
  }
  std::vector<int8_t> flip(nf, -1);
  std::vector<int32_t> component;
  for (size_t seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    component.assign(1, int32_t(seed));
    flip[seed] = 0;
    bool closed = true;
    for (size_t i = 0; i < component.size(); ++i) {
      const int32_t f = component[i];
      closed = closed && !open_face[size_t(f)];
      for (int32_t j = start[size_t(f)]; j < start[size_t(f) + 1]; ++j) {
        const auto [g, same] = next[size_t(j)];
        const int8_t wanted = int8_t(flip[size_t(f)] ^ int8_t(same));
        if (flip[size_t(g)] < 0) {
          flip[size_t(g)] = wanted;
          component.push_back(g);
        } else if (flip[size_t(g)] != wanted) {
          throw TopologyError("the surface is not orientable (it has no inside to thicken, as a Möbius band has "
                              "none): its faces cannot all be turned one way round " +
                              place(s.positions[size_t(s.triangles[size_t(g)][0])]));
        }
      }
    }
    if (!closed) continue;
    const Vec3d centre = to_double(s.positions[size_t(s.triangles[seed][0])]);
    double volume = 0;
    for (const int32_t f : component) {
      Triangle t = s.triangles[size_t(f)];
      if (flip[size_t(f)]) std::swap(t[1], t[2]);
      volume += dot(to_double(s.positions[size_t(t[0])]) - centre,
                    cross(to_double(s.positions[size_t(t[1])]) - centre, to_double(s.positions[size_t(t[2])]) - centre));
    }
    if (volume < 0)
      for (const int32_t f : component) flip[size_t(f)] ^= 1;
  }
  for (size_t f = 0; f < nf; ++f)
    if (flip[f]) std::swap(s.triangles[f][1], s.triangles[f][2]);
}

// The quads' corners: where they are, which way is out, and which corners neighbour.
struct Corners {
  std::vector<Vec3d> normal;        // unit, outward (zero for a corner of no quad)
  std::vector<uint8_t> inward;      // per quad: its corners go round inward
  std::vector<Triangle> halves;     // each quad's two halves either side of its 0-2 fold, outward
  std::vector<int32_t> start, next; // neighbours along the halves' sides (CSR)
};

// The halves turned as the oriented surface's triangles in them are, so that their
// normals point out; each corner's normal weighted by the halves' angles there.
Corners corners_of(const QuadMesh& m, const Surface& s) {
  const size_t nq = size_t(m.num_quads());
  std::vector<double> facing(nq, 0);
  for (size_t f = 0; f < s.triangles.size(); ++f) {
    const Triangle& t = s.triangles[f];
    const auto& c = m.quads[size_t(s.quad[f])];
    const Vec3d a = to_double(m.positions[size_t(c[0])]);
    const Vec3d quad_normal = cross(to_double(m.positions[size_t(c[2])]) - a,
                                    to_double(m.positions[size_t(c[3])]) - to_double(m.positions[size_t(c[c[1] < 0 ? 0 : 1])]));
    const Vec3d p = to_double(s.positions[size_t(t[0])]);
    facing[size_t(s.quad[f])] += dot(cross(to_double(s.positions[size_t(t[1])]) - p, to_double(s.positions[size_t(t[2])]) - p), quad_normal);
  }
  Corners k;
  k.normal.assign(m.positions.size(), Vec3d{});
  k.inward.resize(nq);
  for (size_t q = 0; q < nq; ++q) k.inward[q] = facing[q] < 0;
  std::vector<std::pair<int32_t, int32_t>> edges;
  for (size_t q = 0; q < nq; ++q) {
    const auto& c = m.quads[q];
    for (const Triangle half : {Triangle{c[0], c[1], c[2]}, Triangle{c[0], c[2], c[3]}}) {
      if (half[1] < 0) continue; // a half quad has one half
      const Triangle t = facing[q] < 0 ? Triangle{half[0], half[2], half[1]} : half;
      k.halves.push_back(t);
      const Vec3d p[3] = {to_double(m.positions[size_t(t[0])]), to_double(m.positions[size_t(t[1])]),
                          to_double(m.positions[size_t(t[2])])};
      Vec3d n = cross(p[1] - p[0], p[2] - p[0]);
      if (const double length = norm(n); length > 0) n = n * (1 / length);
      for (int i = 0; i < 3; ++i) {
        const Vec3d e1 = p[(i + 1) % 3] - p[i], e2 = p[(i + 2) % 3] - p[i];
        k.normal[size_t(t[size_t(i)])] = k.normal[size_t(t[size_t(i)])] + n * std::atan2(norm(cross(e1, e2)), dot(e1, e2));
        edges.push_back({t[size_t(i)], t[size_t((i + 1) % 3)]});
        edges.push_back({t[size_t((i + 1) % 3)], t[size_t(i)]});
      }
    }
  }
  for (Vec3d& n : k.normal)
    if (const double length = norm(n); length > 0) n = n * (1 / length);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  k.start.assign(m.positions.size() + 1, 0);
  for (const auto& e : edges) ++k.start[size_t(e.first) + 1];
  std::partial_sum(k.start.begin(), k.start.end(), k.start.begin());
  for (const auto& e : edges) k.next.push_back(e.second);
  return k;
}

// Distances to the surface (CGAL's AABB tree; its queries are safe to run in parallel).
class Distance {
public:
  Distance(std::span<const Vec3> positions, std::span<const Triangle> triangles) {
    triangles_.reserve(triangles.size());
    for (const Triangle& t : triangles) {
      const auto point = [&](int32_t v) { return K::Point_3(positions[size_t(v)].x, positions[size_t(v)].y, positions[size_t(v)].z); };
      triangles_.emplace_back(point(t[0]), point(t[1]), point(t[2]));
    }
    tree_.rebuild(triangles_.begin(), triangles_.end());
    tree_.accelerate_distance_queries();
  }
  double operator()(Vec3d p) const { return std::sqrt(tree_.squared_distance(K::Point_3(p.x, p.y, p.z))); }
  Vec3d closest(Vec3d p) const {
    const K::Point_3 c = tree_.closest_point(K::Point_3(p.x, p.y, p.z));
    return {c.x(), c.y(), c.z()};
  }

private:
  using K = CGAL::Simple_cartesian<double>;
  using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<K::Triangle_3>::const_iterator>;
  std::vector<K::Triangle_3> triangles_;
  CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> tree_;
};

// How far each corner moves in along its normal: until it lies `wall` from the surface,
// or, in a part thinner than two walls, to 0.45 of the way across (where its distance
// to the surface stops growing: past the middle), and no nearer the middle than half
// the `gap` the insides must keep (the clearance). In steps of an eighth of the wall, up
// to 4 walls (a sharp rim moves in further than the faces beside it).
std::vector<double> march_inward(const QuadMesh& m, const Corners& k, const Distance& distance, double wall, double gap) {
  std::vector<double> along(m.positions.size(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, along.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v < r.end(); ++v) {
      if (norm(k.normal[v]) == 0) continue;
      const Vec3d p = to_double(m.positions[v]);
      const double step = wall / 8;
      double before = 0;
      along[v] = 32 * step;
      for (int i = 1; i <= 32; ++i) {
        const double d = distance(p - k.normal[v] * (i * step));
        if (d >= wall) {
          along[v] = (i - 1 + (wall - before) / (d - before)) * step;
          break;
        }
        if (d <= before) {
          along[v] = std::max(0.0, std::min(0.9 * (i - 1) * step, (i - 1) * step - gap / 2));
          break;
        }
        before = d;
      }
    }
  });
  return along;
}

// Each corner's inside: moved in by `along`, then onto the points that lie as far from
// the surface as it does there (at most the wall): near a sharp convex bend, a corner
// moved straight in comes nearer the other side of the bend than the wall, and is pushed
// from it until the walls from both sides are kept (the insides of the bend's corners
// then meet along the inside of the bend instead of folding over it).
std::vector<Vec3d> settle(const QuadMesh& m, const Corners& k, const Distance& distance, const std::vector<double>& along,
                          double wall) {
  std::vector<Vec3d> inside(m.positions.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, inside.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v < r.end(); ++v) {
      Vec3d q = to_double(m.positions[v]) - k.normal[v] * along[v];
      const double target = std::min(wall, distance(q));
      for (int i = 0; i < 6 && target > 0; ++i) {
        const Vec3d c = distance.closest(q);
        const double d = norm(q - c);
        if (d == 0) break;
        q = c + (q - c) * (target / d);
      }
      inside[v] = q;
    }
  });
  return inside;
}

std::vector<Vec3> to_floats(const std::vector<Vec3d>& points) {
  std::vector<Vec3> out(points.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = to_float(points[v]);
  return out;
}

// Draws corner v's inside a `share` of the way back towards the corner.
void draw_in(std::vector<Vec3d>& inside, const QuadMesh& m, size_t v, double share) {
  const Vec3d p = to_double(m.positions[v]);
  inside[v] = p + (inside[v] - p) * (1 - share);
}

// Draws in the corners of halves whose inside turns more than about 70 degrees from
// their outside (folding over), until none does.
void unfold(std::vector<Vec3d>& inside, const QuadMesh& m, const Corners& k) {
  for (int round = 0; round < 40; ++round) {
    std::vector<uint8_t> lower(inside.size(), 0);
    bool any = false;
    for (const Triangle& t : k.halves) {
      const Vec3d a = to_double(m.positions[size_t(t[0])]), ia = inside[size_t(t[0])];
      const Vec3d out = cross(to_double(m.positions[size_t(t[1])]) - a, to_double(m.positions[size_t(t[2])]) - a);
      const Vec3d in = cross(inside[size_t(t[1])] - ia, inside[size_t(t[2])] - ia);
      if (norm(out) == 0 || dot(in, out) > 0.35 * norm(in) * norm(out)) continue;
      for (const int32_t v : t) lower[size_t(v)] = 1;
      any = true;
    }
    if (!any) return;
    for (size_t v = 0; v < inside.size(); ++v)
      if (lower[v]) draw_in(inside, m, v, 0.3);
  }
}

// The solid of the surface's triangles that `take` keeps: the triangles (outside), the
// same at `inner` and turned (inside), and walls along the edges where the kept
// triangles end, each wall two triangles between the edge and its inward copy. `from`
// gets, per face of the solid, the surface triangle it was made from.
PolygonMesh solid_of(const Surface& s, const std::vector<Side>& sides, const std::vector<Vec3>& inner,
                     const std::vector<uint8_t>& take, std::vector<int32_t>& from) {
  std::vector<int32_t> id(s.positions.size(), -1);
  std::vector<int32_t> used;
  for (size_t f = 0; f < s.triangles.size(); ++f)
    if (take[f])
      for (const int32_t v : s.triangles[f])
        if (id[size_t(v)] < 0) {
          id[size_t(v)] = int32_t(used.size());
          used.push_back(v);
        }
  const int32_t n_outer = int32_t(used.size());
  PolygonMesh solid;
  solid.positions.reserve(2 * used.size());
  for (const int32_t v : used) solid.positions.push_back(s.positions[size_t(v)]);
  for (const int32_t v : used) solid.positions.push_back(inner[size_t(v)]);
  from.clear();
  for (int inside = 0; inside < 2; ++inside)
    for (size_t f = 0; f < s.triangles.size(); ++f)
      if (take[f]) {
        const Triangle& t = s.triangles[f];
        if (inside) solid.add_face({n_outer + id[size_t(t[0])], n_outer + id[size_t(t[2])], n_outer + id[size_t(t[1])]});
        else solid.add_face({id[size_t(t[0])], id[size_t(t[1])], id[size_t(t[2])]});
        from.push_back(int32_t(f));
      }
  // An edge a -> b of a kept triangle with no kept triangle on its other side gets the
  // wall b, a, a', b', which goes the other way along each of its edges than the faces
  // beside it; split along the diagonal from the edge's lower vertex, so that the solid
  // on the other side of a cut gets the very same two triangles.
  for (size_t i = 0; i < sides.size(); ++i) {
    const Side& side = sides[i];
    if (!take[size_t(side.face)]) continue;
    const bool before = i > 0 && same_edge(sides[i - 1], side) && take[size_t(sides[i - 1].face)];
    const bool after = i + 1 < sides.size() && same_edge(side, sides[i + 1]) && take[size_t(sides[i + 1].face)];
    if (before || after) continue;
    const int32_t a = id[size_t(side.forward ? side.low : side.high)], b = id[size_t(side.forward ? side.high : side.low)];
    if (side.forward) { // a is the lower
      solid.add_face({b, a, n_outer + b});
      solid.add_face({a, n_outer + a, n_outer + b});
    } else {
      solid.add_face({b, a, n_outer + a});
      solid.add_face({b, n_outer + a, n_outer + b});
    }
    from.push_back(side.face);
    from.push_back(side.face);
  }
  return solid;
}

// The solids of the two regions drawn apart by `gaps` (duotone_regions), the inside at
// `inner` (per corner), each turned outward as its quad, with its own walls; their least
// distance apart (from a corner or side midpoint of either's faces to the other).
// Returns the quads of the faces that come nearer the other solid than `near`. Throws
// TopologyError for a solid that crosses itself.
std::vector<int32_t> draw_apart(SplitShell& out, const Duotone& duotone, TileStyle style, const Corners& corners,
                                std::span<const Vec3> inner, std::span<const float> gaps, double near) {
  const QuadMesh& m = duotone.quads;
  RegionOrigins origins;
  Surface a = weld(duotone_regions(duotone, style, m.positions, &origins, gaps), origins);
  for (size_t f = 0; f < a.triangles.size(); ++f)
    if (corners.inward[size_t(a.quad[f])]) std::swap(a.triangles[f][1], a.triangles[f][2]);
  const std::vector<Side> sides = sides_of(a);
  const std::vector<Vec3> inside = welded_positions(a, duotone_regions(duotone, style, inner, nullptr, gaps));
  std::array<std::vector<int32_t>, 2> from;
  for (int k = 0; k < 2; ++k) {
    std::vector<uint8_t> region(a.triangles.size());
    for (size_t f = 0; f < region.size(); ++f) region[f] = a.region[f] == k;
    out.solids[size_t(k)] = solid_of(a, sides, inside, region, from[size_t(k)]);
    if (const std::vector<int32_t> crossing = self_intersecting_faces(out.solids[size_t(k)]); !crossing.empty())
      throw TopologyError("shell: a piece drawn back by the clearance crosses itself near " +
                          place(a.positions[size_t(a.triangles[size_t(from[size_t(k)][size_t(crossing[0])])][0])]) +
                          " (a smaller --clearance or a coarser --spacing may not)");
  }
  const std::array<std::vector<int32_t>, 2> nearer = measure_apart(out, near);
  std::vector<int32_t> quads;
  for (int k = 0; k < 2; ++k)
    for (const int32_t f : nearer[size_t(k)]) quads.push_back(a.quad[size_t(from[size_t(k)][size_t(f)])]);
  std::sort(quads.begin(), quads.end());
  quads.erase(std::unique(quads.begin(), quads.end()), quads.end());
  return quads;
}

// Widens the gaps of these quads by half, each once (a side's on both quads on it);
// false where one would pass 0.2.
bool widen(std::vector<float>& gaps, const QuadMesh& m, std::span<const int32_t> quads) {
  std::vector<uint8_t> wider(gaps.size(), 0);
  for (const int32_t q : quads)
    for (int k = 0; k < 5; ++k) {
      wider[5 * size_t(q) + size_t(k)] = 1;
      if (const int32_t n = k < 4 ? m.neighbors[size_t(q)][size_t(k)] : -1; n >= 0) wider[5 * size_t(n / 4) + size_t(n % 4)] = 1;
    }
  for (size_t i = 0; i < gaps.size(); ++i)
    if (wider[i] && (gaps[i] *= 1.5f) > 0.2f) return false;
  return true;
}

// The shell whose inside follows the quads' corners (see duotone_shell), of the oriented
// surface `s`. Throws TopologyError where it cannot.
SplitShell quad_shell(const Duotone& duotone, TileStyle style, const ShellOptions& options, const Surface& s,
                      const std::vector<Side>& sides) {
  const double h = options.thickness;
  const QuadMesh& m = duotone.quads;
  {
    PolygonMesh outside;
    outside.positions = s.positions;
    for (const Triangle& t : s.triangles) outside.add_face(t);
    if (const std::vector<int32_t> crossing = self_intersecting_faces(outside); !crossing.empty())
      throw TopologyError("shell: the surface crosses or touches itself near " +
                          place(s.positions[size_t(s.triangles[size_t(crossing[0])][0])]) +
                          ", so no wall can be made inside it (a remesh at another --spacing may not)");
  }
  const Corners corners = corners_of(m, s);

  const Distance distance(s.positions, s.triangles);
  std::vector<Vec3d> inside = settle(m, corners, distance, march_inward(m, corners, distance, h, options.clearance), h);
  unfold(inside, m, corners);

  SplitShell out;
  std::array<std::vector<uint8_t>, 3> take;
  for (int k = 0; k < 2; ++k) {
    take[size_t(k)].resize(s.triangles.size());
    for (size_t f = 0; f < s.triangles.size(); ++f) take[size_t(k)][f] = s.region[f] == k;
  }
  take[2].assign(s.triangles.size(), 1); // the whole shell: the two regions' insides must not cross either
  std::vector<int32_t> from;
  // Where the inside still crosses itself or the outside, the corners of the quads there
  // are drawn in.
  for (int attempt = 0;; ++attempt) {
    const std::vector<Vec3> inner = welded_positions(s, duotone_regions(duotone, style, to_floats(inside)));
    std::vector<uint8_t> tangled(inside.size(), 0);
    bool crossing = false;
    Vec3 where;
    for (int k = 0; k < 3; ++k) {
      PolygonMesh solid = solid_of(s, sides, inner, take[size_t(k)], from);
      for (const int32_t f : self_intersecting_faces(solid)) {
        const int32_t t = from[size_t(f)];
        for (const int32_t v : m.quads[size_t(s.quad[size_t(t)])])
          if (v >= 0) tangled[size_t(v)] = 1;
        if (!crossing) where = s.positions[size_t(s.triangles[size_t(t)][0])];
        crossing = true;
      }
      if (k < 2) out.solids[size_t(k)] = std::move(solid);
    }
    if (!crossing) break;
    if (attempt == 5)
      throw TopologyError("shell: the inside of the wall crosses itself or the outside near " + place(where) +
                          ", where the surface folds too sharply or is too thin for a hollow shell (a finer "
                          "--spacing, a thinner --shell or a larger --model-size may do)");
    for (size_t v = 0; v < inside.size(); ++v)
      if (tangled[v] == 1)
        for (int32_t j = corners.start[v]; j < corners.start[v + 1]; ++j) tangled[size_t(corners.next[size_t(j)])] |= 2;
    for (size_t v = 0; v < inside.size(); ++v)
      if (tangled[v]) draw_in(inside, m, v, tangled[v] & 1 ? 0.5 : 0.2);
    unfold(inside, m, corners);
  }
  // Apart: the same inside, each region drawn back from the cut on both surfaces. Where
  // the wall slants (the inside sheared against the outside) a piece's edge comes nearer
  // the other's wall: the gaps there widen, a few times, until the pieces are 0.45 of
  // the clearance apart everywhere.
  if (options.clearance > 0) {
    const std::vector<Vec3> at_inside = to_floats(inside);
    std::vector<float> gaps = duotone_gaps(duotone, style, m.positions, at_inside, options.clearance);
    // A gap over a fifth of its quad leaves too little of the quad: sampled instead.
    if (const auto widest = std::max_element(gaps.begin(), gaps.end()); *widest > 0.2f)
      throw TopologyError("shell: the clearance is too wide for the quads near " +
                          place(m.positions[size_t(m.quads[size_t((widest - gaps.begin()) / 5)][0])]));
    for (int round = 0;; ++round) {
      const std::vector<int32_t> near = draw_apart(out, duotone, style, corners, at_inside, gaps, 0.45 * options.clearance);
      if (near.empty()) break;
      if (round == 4 || !widen(gaps, m, near))
        throw TopologyError("shell: the pieces come within " + std::to_string(out.apart) + " of each other near " +
                            place(out.apart_at) + ", less than 0.45 of the clearance, where the wall slants too far " +
                            "to draw them further apart (a smaller --clearance or a coarser --spacing may not)");
    }
  }

  for (int k = 0; k < 2; ++k) {
    const PolygonMesh& solid = out.solids[size_t(k)];
    for (int32_t f = 0; f < solid.num_faces(); ++f) {
      const std::span<const int32_t> t = solid.face(f);
      out.volumes[size_t(k)] += dot(to_double(solid.positions[size_t(t[0])]),
                                    cross(to_double(solid.positions[size_t(t[1])]), to_double(solid.positions[size_t(t[2])]))) / 6;
    }
  }
  // The wall at a corner: how far its inside lies from the surface.
  out.thinnest = INFINITY;
  for (size_t v = 0; v < inside.size(); ++v) {
    if (norm(corners.normal[v]) == 0) continue;
    const double wall = std::min(h, distance(inside[v]));
    if (wall < h * (1 - 1e-3)) ++out.reduced_corners;
    if (wall < options.min_thickness) ++out.below_floor_corners;
    if (wall < out.thinnest) {
      out.thinnest = wall;
      out.thinnest_at = m.positions[v];
    }
  }
  return out;
}

} // namespace

std::array<std::vector<int32_t>, 2> measure_apart(SplitShell& out, double near) {
  out.apart = INFINITY;
  std::array<std::vector<int32_t>, 2> nearer;
  for (int k = 0; k < 2; ++k) {
    const PolygonMesh& solid = out.solids[size_t(k)];
    const PolygonMesh& other = out.solids[size_t(1 - k)];
    std::vector<Triangle> triangles;
    for (int32_t f = 0; f < other.num_faces(); ++f) triangles.push_back({other.face(f)[0], other.face(f)[1], other.face(f)[2]});
    const Distance to_other(other.positions, triangles);
    // Each face's corners and the midpoints of its sides (where two slanted walls come
    // nearer than their corners do).
    for (int32_t f = 0; f < solid.num_faces(); ++f) {
      const std::span<const int32_t> t = solid.face(f);
      bool close = false;
      for (size_t i = 0; i < 3; ++i) {
        const Vec3d p = to_double(solid.positions[size_t(t[i])]), q = to_double(solid.positions[size_t(t[(i + 1) % 3])]);
        for (const Vec3d x : {p, (p + q) * 0.5}) {
          const double d = to_other(x);
          if (d < out.apart) out.apart = d, out.apart_at = to_float(x);
          close = close || d < near;
        }
      }
      if (close) nearer[size_t(k)].push_back(f);
    }
  }
  return nearer;
}

std::string place(Vec3 p) {
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

SplitShell duotone_shell(const Duotone& duotone, TileStyle style, const ShellOptions& options) {
  const double h = options.thickness;
  if (!(h > 0) || !std::isfinite(h)) throw ParameterError("shell", " must be a positive number (the wall's thickness)");
  if (!(options.clearance >= 0) || !std::isfinite(options.clearance))
    throw ParameterError("clearance", " must be a number, at least 0 (the gap between the two pieces)");
  if (!(options.min_thickness >= 0) || options.min_thickness > h)
    throw ParameterError("shell", " (" + std::to_string(h) + ") is thinner than the thinnest wall the printer makes (" +
                                      std::to_string(options.min_thickness) + ")");
  if (options.clearance > 0) {
    // The gap is about 1.2 of the clearance wide where sampled, and a colour's band about
    // half a quad: past a sixth of the quads' usual side, the gap leaves crumbs.
    const QuadMesh& m = duotone.quads;
    std::vector<float> sides;
    for (int32_t q = 0; q < m.num_quads(); ++q)
      if (!m.is_half(q))
        for (size_t k = 0; k < 4; ++k)
          sides.push_back(float(norm(m.positions[size_t(m.quads[size_t(q)][k])] - m.positions[size_t(m.quads[size_t(q)][(k + 1) % 4])])));
    if (sides.empty()) throw TopologyError("shell: the surface has no faces");
    const auto middle = sides.begin() + std::ptrdiff_t(sides.size() / 2);
    std::nth_element(sides.begin(), middle, sides.end());
    if (const double most = *middle / 6; options.clearance > most)
      throw ParameterError("clearance", " (" + std::to_string(options.clearance) + ") is too wide for quads of " +
                                            std::to_string(*middle) + " (the gap would cut the colours' bands into crumbs): at most " +
                                            std::to_string(most) + ", or a coarser --spacing");
  }
  RegionOrigins origins;
  Surface s = weld(duotone_regions(duotone, style, duotone.quads.positions, &origins), origins);
  if (s.triangles.empty()) throw TopologyError("shell: the surface has no faces");
  orient(s, sides_of(s));
  const std::vector<Side> sides = sides_of(s); // again: orient() turned triangles round
  try {
    return quad_shell(duotone, style, options, s, sides);
  } catch (const TopologyError&) {
    // No wall follows the quads, or their pieces cannot be drawn apart: sampled instead.
  }
  return sampled_shell({s.positions, s.triangles, s.region}, h, options.clearance);
}

} // namespace meander
