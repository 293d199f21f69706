#include "meander/closest_points.h"

#include "embree/embree_scene.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace meander {

namespace {

// Where on triangle abc the point closest to p lies.
enum class Region { inside, a, b, c, ab, ac, bc };

// The point of triangle abc closest to p (Ericson, Real-Time Collision Detection, 5.1.5):
// by the Voronoi region of the triangle's vertices, edges or inside that p lies in.
std::pair<Vec3d, Region> closest_on_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, Region::a};
  const Vec3d bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, Region::b};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + ab * (d1 / (d1 - d3)), Region::ab};
  const Vec3d cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, Region::c};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + ac * (d2 / (d2 - d6)), Region::ac};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return {b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), Region::bc};
  const double denominator = va + vb + vc;
  // A degenerate triangle (all three zero) is met by the edge tests above unless p is on it.
  if (!(denominator > 0)) return {a, Region::a};
  return {a + ab * (vb / denominator) + ac * (vc / denominator), Region::inside};
}

struct Triangles {
  std::vector<Vec3> positions;
  std::vector<std::array<int32_t, 3>> corners;
  // The triangles around each vertex v: around[around_start[v]] up to around_start[v + 1].
  std::vector<int32_t> around_start, around;

  std::array<Vec3d, 3> at(int32_t t) const {
    const std::array<int32_t, 3>& v = corners[size_t(t)];
    return {to_double(positions[size_t(v[0])]), to_double(positions[size_t(v[1])]), to_double(positions[size_t(v[2])])};
  }
};

// One query's best triangle so far. Of triangles equally near, the lowest numbered wins,
// so that the answer does not depend on the order the tree visits them.
struct Query {
  const Triangles* triangles;
  Vec3d p;
  Vec3d best{};
  double best_squared = std::numeric_limits<double>::infinity();
  int32_t triangle = -1;

  bool offer(int32_t t) {
    const auto [a, b, c] = triangles->at(t);
    const Vec3d q = closest_on_triangle(p, a, b, c).first;
    const double d = dot(q - p, q - p);
    if (d > best_squared || (d == best_squared && t > triangle)) return false;
    best = q;
    best_squared = d;
    triangle = t;
    return true;
  }
  // The query's radius: the best distance and a millionth of it and of p's coordinates
  // more, above the rounding of Embree's float distances to boxes, so that ties are still
  // visited whatever the tree and the processor.
  float radius() const {
    const double r = std::sqrt(best_squared);
    return float(r + 1e-6 * (r + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)})));
  }
};

bool visit(RTCPointQueryFunctionArguments* args) {
  Query& q = *static_cast<Query*>(args->userPtr);
  if (!q.offer(int32_t(args->primID))) return false;
  args->query->radius = q.radius();
  return true;
}

// A range query: each triangle within `within` of p handed to `near` until it holds.
struct NearQuery {
  const Triangles* triangles;
  Vec3d p;
  double within;
  const std::function<bool(Vec3d, const std::array<Vec3d, 3>&)>* near;
  bool found = false;
};

bool visit_near(RTCPointQueryFunctionArguments* args) {
  NearQuery& q = *static_cast<NearQuery*>(args->userPtr);
  if (q.found) return false; // the rest of a leaf of the tree
  const std::array<Vec3d, 3> corners = q.triangles->at(int32_t(args->primID));
  const Vec3d c = closest_on_triangle(q.p, corners[0], corners[1], corners[2]).first;
  if (dot(c - q.p, c - q.p) > q.within * q.within || !(*q.near)(c, corners)) return false;
  q.found = true;
  args->query->radius = 0; // no need to look further
  return true;
}

} // namespace

struct ClosestPoints::Tree {
  Triangles triangles;
  std::optional<EmbreeScene> scene;
};

ClosestPoints::ClosestPoints(const PolygonMesh& surface) : tree_(std::make_unique<Tree>()) {
  Tree& t = *tree_;
  t.triangles.positions = surface.positions;
  std::vector<std::array<int32_t, 3>>& corners = t.triangles.corners;
  corners.reserve(size_t(surface.num_corners() - 2 * surface.num_faces()));
  for (int32_t f = 0; f < surface.num_faces(); ++f) {
    const std::span<const int32_t> face = surface.face(f);
    for (size_t i = 1; i + 1 < face.size(); ++i) corners.push_back({face[0], face[i], face[i + 1]});
  }
  if (corners.empty()) return;
  std::vector<int32_t>& start = t.triangles.around_start;
  start.assign(surface.positions.size() + 1, 0);
  for (const std::array<int32_t, 3>& v : corners)
    for (const int32_t corner : v) ++start[size_t(corner) + 1];
  for (size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  t.triangles.around.resize(size_t(start.back()));
  std::vector<int32_t> filled(start.begin(), start.end() - 1);
  for (size_t triangle = 0; triangle < corners.size(); ++triangle)
    for (const int32_t corner : corners[triangle]) t.triangles.around[size_t(filled[size_t(corner)]++)] = int32_t(triangle);
  t.scene.emplace("closest points", RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geometry = rtcNewGeometry(t.scene->device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  set_vertices(geometry, surface.positions);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, corners.data(), 0,
                             sizeof(std::array<int32_t, 3>), corners.size());
  t.scene->attach(geometry);
  t.scene->commit();
}

ClosestPoints::~ClosestPoints() = default;
ClosestPoints::ClosestPoints(ClosestPoints&&) noexcept = default;
ClosestPoints& ClosestPoints::operator=(ClosestPoints&&) noexcept = default;

Vec3d ClosestPoints::closest(Vec3d p) const { return closest_hit(p).point; }

ClosestPoints::Hit ClosestPoints::closest_hit(Vec3d p) const { return closest_hit(p, Hit{}); }

ClosestPoints::Hit ClosestPoints::closest_hit(Vec3d p, const Hit& hint) const {
  return closest_hit(p, hint, std::numeric_limits<double>::infinity());
}

ClosestPoints::Hit ClosestPoints::closest_hit(Vec3d p, const Hit& hint, double within) const {
  if (!tree_->scene) return {p, {}};
  Query q{.triangles = &tree_->triangles, .p = p, .best_squared = within * within};
  if (hint.triangle >= 0 && size_t(hint.triangle) < tree_->triangles.corners.size()) q.offer(hint.triangle);
  RTCPointQuery query;
  query.x = float(p.x);
  query.y = float(p.y);
  query.z = float(p.z);
  query.radius = q.radius();
  query.time = 0;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(tree_->scene->scene(), &query, &context, visit, &q);
  // Only a surface of degenerate triangles, which Embree leaves out, has none.
  if (q.triangle < 0) return {p, {}};
  return hit_on(q.triangle, q.best);
}

bool ClosestPoints::any_near(Vec3d p, double within,
                             const std::function<bool(Vec3d closest, const std::array<Vec3d, 3>& corners)>& near) const {
  if (!tree_->scene) return false;
  NearQuery q{.triangles = &tree_->triangles, .p = p, .within = within, .near = &near};
  RTCPointQuery query;
  query.x = float(p.x);
  query.y = float(p.y);
  query.z = float(p.z);
  query.radius = float(within * (1 + 1e-6)) + 1e-6f * float(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
  query.time = 0;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(tree_->scene->scene(), &query, &context, visit_near, &q);
  return q.found;
}

ClosestPoints::Hit ClosestPoints::hit_on(int32_t triangle, Vec3d point) const {
  const auto [a, b, c] = tree_->triangles.at(triangle);
  const Vec3d n = cross(b - a, c - a);
  const double length = norm(n);
  return {point, length > 0 ? n * (1 / length) : Vec3d{}, triangle};
}

ClosestPoints::Hit ClosestPoints::nearby_hit(Vec3d p, const Hit& from) const {
  const Triangles& triangles = tree_->triangles;
  if (from.triangle < 0 || size_t(from.triangle) >= triangles.corners.size()) return closest_hit(p);
  // A walk longer than this (a point that moved across many faces of a fine surface)
  // is left to the tree.
  constexpr int kSteps = 64;
  int32_t t = from.triangle;
  auto [a, b, c] = triangles.at(t);
  auto [q, region] = closest_on_triangle(p, a, b, c);
  double best = dot(q - p, q - p);
  for (int step = 0; step < kSteps; ++step) {
    // Inside t, q is nearest of all points around it on the surface.
    if (region == Region::inside) return hit_on(t, q);
    // Else the faces that may be nearer are those around the vertex q lies on, or around
    // either end of its edge (not only across it: past a sliver of a face whose corners
    // lie in a line, too). Of faces as near, the lowest numbered, so that each step goes
    // nearer or lower and the walk ends.
    const std::array<int32_t, 3>& v = triangles.corners[size_t(t)];
    const auto [first, second] = [&]() -> std::pair<int32_t, int32_t> {
      switch (region) {
      case Region::a: return {v[0], -1};
      case Region::b: return {v[1], -1};
      case Region::c: return {v[2], -1};
      case Region::ab: return {v[0], v[1]};
      case Region::ac: return {v[0], v[2]};
      default: return {v[1], v[2]};
      }
    }();
    int32_t next = -1;
    std::pair<Vec3d, Region> there;
    for (const int32_t corner : {first, second}) {
      if (corner < 0) continue;
      for (int32_t k = triangles.around_start[size_t(corner)]; k < triangles.around_start[size_t(corner) + 1]; ++k) {
        const int32_t u = triangles.around[size_t(k)];
        if (u == t) continue;
        const auto [ua, ub, uc] = triangles.at(u);
        const std::pair<Vec3d, Region> on = closest_on_triangle(p, ua, ub, uc);
        const double d = dot(on.first - p, on.first - p);
        if (d < best || (d == best && u < (next < 0 ? t : next))) {
          best = d;
          next = u;
          there = on;
        }
      }
    }
    if (next < 0) return hit_on(t, q);
    t = next;
    std::tie(q, region) = there;
  }
  return closest_hit(p, hit_on(t, q));
}

std::vector<ClosestPoints::Hit> ClosestPoints::path(const Hit& a, const Hit& b, double step, double longest) const {
  const Triangles& triangles = tree_->triangles;
  const auto valid = [&](const Hit& h) { return h.triangle >= 0 && size_t(h.triangle) < triangles.corners.size(); };
  if (!valid(a) || !valid(b) || !(step > 0)) return {};
  // The way's corners: a, then points on the faces' edges, then b, and the triangle each
  // piece crosses. The shortest path (A*, the straight distance to b as the estimate)
  // over the vertices and points on the edges about a step apart (so that faces larger
  // than a step are crossed about straight), each joined to the others of the faces it
  // lies on.
  std::vector<Vec3d> way{a.point};
  std::vector<int32_t> across;
  if (a.triangle != b.triangle) {
    // A vertex {v, -1, 0}, or point k of the edge from u to w > u, {u, w, k}.
    using Node = std::array<int32_t, 3>;
    auto at = [&](int32_t v) { return to_double(triangles.positions[size_t(v)]); };
    auto pieces = [&](int32_t u, int32_t w) { return std::max(1, int(std::ceil(norm(at(w) - at(u)) / step))); };
    auto position = [&](const Node& n) {
      return n[1] < 0 ? at(n[0]) : at(n[0]) + (at(n[1]) - at(n[0])) * (double(n[2]) / pieces(n[0], n[1]));
    };
    // Every node on triangle t's edges, to `visit`.
    auto for_each_node = [&](int32_t t, auto&& visit) {
      const std::array<int32_t, 3>& v = triangles.corners[size_t(t)];
      for (int e = 0; e < 3; ++e) {
        const int32_t u = std::min(v[size_t(e)], v[size_t(e + 1) % 3]), w = std::max(v[size_t(e)], v[size_t(e + 1) % 3]);
        visit(Node{v[size_t(e)], -1, 0});
        for (int k = 1; k < pieces(u, w); ++k) visit(Node{u, w, k});
      }
    };
    // The triangles a node lies on.
    auto for_each_triangle = [&](const Node& n, auto&& visit) {
      for (int32_t k = triangles.around_start[size_t(n[0])]; k < triangles.around_start[size_t(n[0]) + 1]; ++k) {
        const int32_t t = triangles.around[size_t(k)];
        const std::array<int32_t, 3>& v = triangles.corners[size_t(t)];
        if (n[1] < 0 || std::find(v.begin(), v.end(), n[1]) != v.end()) visit(t);
      }
    };
    struct Reached {
      double distance;
      Node before;
      int32_t triangle; // that the piece from `before` crosses
    };
    struct Hash {
      size_t operator()(const Node& n) const {
        return std::hash<uint64_t>()((uint64_t(uint32_t(n[0])) << 32 | uint32_t(n[1])) * 31 + uint32_t(n[2]));
      }
    };
    std::unordered_map<Node, Reached, Hash> reached;
    // (distance + the straight distance left, distance, node)
    using Entry = std::tuple<double, double, Node>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    constexpr Node none{-1, -1, -1};
    auto offer = [&](const Node& n, double d, const Node& from, int32_t t) {
      const double estimate = d + norm(b.point - position(n));
      if (estimate >= longest) return;
      if (auto [it, added] = reached.try_emplace(n, Reached{d, from, t}); added || d < it->second.distance) {
        it->second = {d, from, t};
        queue.push({estimate, d, n});
      }
    };
    for_each_node(a.triangle, [&](const Node& n) { offer(n, norm(position(n) - a.point), none, a.triangle); });
    double shortest = longest;
    Node last = none;
    while (!queue.empty()) {
      const auto [estimate, d, n] = queue.top();
      queue.pop();
      if (estimate >= shortest) break;
      if (d > reached[n].distance) continue;
      const Vec3d p = position(n);
      for_each_triangle(n, [&](int32_t t) {
        if (t == b.triangle)
          if (const double total = d + norm(b.point - p); total < shortest) {
            shortest = total;
            last = n;
          }
        for_each_node(t, [&](const Node& m) { offer(m, d + norm(position(m) - p), n, t); });
      });
    }
    if (last == none) return {};
    for (Node n = last; n != none; n = reached[n].before) {
      way.push_back(position(n));
      across.push_back(reached[n].triangle);
    }
    std::reverse(way.begin() + 1, way.end());
    std::reverse(across.begin(), across.end());
  }
  way.push_back(b.point);
  across.push_back(b.triangle);
  double length = 0;
  for (size_t i = 1; i < way.size(); ++i) length += norm(way[i] - way[i - 1]);
  // Points at equal steps along the way.
  const int pieces = std::max(1, int(std::floor(length / step + 0.5)));
  std::vector<Hit> points;
  size_t segment = 1;
  double before = 0; // the way's length up to corner segment - 1
  for (int m = 1; m < pieces; ++m) {
    const double s = length * m / pieces;
    while (segment + 1 < way.size() && before + norm(way[segment] - way[segment - 1]) < s) {
      before += norm(way[segment] - way[segment - 1]);
      ++segment;
    }
    const double piece = norm(way[segment] - way[segment - 1]);
    const Vec3d p = way[segment - 1] + (way[segment] - way[segment - 1]) * (piece > 0 ? (s - before) / piece : 0.0);
    points.push_back(hit_on(across[segment - 1], p));
  }
  return points;
}

void ClosestPoints::project(std::span<Vec3> points, std::span<Vec3> normals) const {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const Hit hit = closest_hit(to_double(points[i]));
      points[i] = to_float(hit.point);
      if (!normals.empty()) normals[i] = to_float(hit.normal);
    }
  });
}

} // namespace meander
