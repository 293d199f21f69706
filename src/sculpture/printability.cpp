#include "meander/printability.h"

#include "meander/check.h"
#include "meander/error.h"
#include "embree/embree_scene.h"

#include <embree3/rtcore.h>
#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace meander {
namespace {

// Geometry in double (Vec3d): float inputs promote exactly, and differences of floats of
// similar magnitude stay exact, so the signs below are exact for the small-integer and
// axis-aligned configurations where ties matter (shared planes, touching corners) and
// correct elsewhere unless a point lies within ~1e-16 relative of a plane.
int sign(double v) { return (v > 0) - (v < 0); }

// The plane through a, b, c, to tell on which side points lie. The cross product and
// the per-axis terms of the error bound are computed once per plane: a pair of
// triangles tests up to six points against each one's plane, and the pair search tests
// tens of millions of pairs.
struct Plane {
  Vec3d a, b, c;
  Vec3d normal;    // (b - a) x (c - a)
  Vec3d magnitude; // per coordinate of the normal, the sum of the absolute products it is made of
  Plane(Vec3d a_, Vec3d b_, Vec3d c_) : a(a_), b(b_), c(c_) {
    const Vec3d ba = b - a, ca = c - a;
    normal = cross(ba, ca);
    magnitude = {std::abs(ba.y * ca.z) + std::abs(ba.z * ca.y), std::abs(ba.z * ca.x) + std::abs(ba.x * ca.z),
                 std::abs(ba.x * ca.y) + std::abs(ba.y * ca.x)};
  }

  // +1 if d lies on the side the normal points to, -1 on the other, 0 in the plane. The
  // sign in double is kept where it clears Shewchuk's error bound for this expression;
  // below it (d almost in the plane, as nearly coplanar faces of smooth ribbons are) the
  // determinant is recomputed in quadruple precision from the float coordinates, which
  // resolves it unless d is within ~1e-30 relative of the plane.
  int side(Vec3d d) const {
    const Vec3d da = d - a;
    const double det = dot(normal, da);
    const double permanent = magnitude.x * std::abs(da.x) + magnitude.y * std::abs(da.y) + magnitude.z * std::abs(da.z);
    if (std::abs(det) > 7.771561172376103e-16 * permanent) return sign(det);
    using Q = __float128;
    const Q bx = Q(b.x) - Q(a.x), by = Q(b.y) - Q(a.y), bz = Q(b.z) - Q(a.z);
    const Q cx = Q(c.x) - Q(a.x), cy = Q(c.y) - Q(a.y), cz = Q(c.z) - Q(a.z);
    const Q dx = Q(d.x) - Q(a.x), dy = Q(d.y) - Q(a.y), dz = Q(d.z) - Q(a.z);
    const Q q = (by * cz - bz * cy) * dx + (bz * cx - bx * cz) * dy + (bx * cy - by * cx) * dz;
    return (q > 0) - (q < 0);
  }
};

// +1 if d lies on the side of plane (a, b, c) that (b - a) x (c - a) points to (see
// Plane::side).
int orient3d(Vec3d a, Vec3d b, Vec3d c, Vec3d d) { return Plane(a, b, c).side(d); }

// The axis along which the normal of (a, b, c) is largest: dropping it projects the
// triangle's plane onto a coordinate plane without collapsing it.
int dominant_axis(Vec3d a, Vec3d b, Vec3d c) {
  const Vec3d n = cross(b - a, c - a);
  const double x = std::abs(n.x), y = std::abs(n.y), z = std::abs(n.z);
  return x >= y && x >= z ? 0 : y >= z ? 1 : 2;
}

// Orientation of a, b, c projected along `axis` (the other two axes in cyclic order).
int orient2d(Vec3d a, Vec3d b, Vec3d c, int axis) {
  const auto uv = [axis](Vec3d p) {
    return axis == 0 ? std::pair{p.y, p.z} : axis == 1 ? std::pair{p.z, p.x} : std::pair{p.x, p.y};
  };
  const auto [ax, ay] = uv(a);
  const auto [bx, by] = uv(b);
  const auto [cx, cy] = uv(c);
  return sign((bx - ax) * (cy - ay) - (by - ay) * (cx - ax));
}

// Closed segments ab and cd, in one plane projected along `axis`.
bool segments_meet_2d(Vec3d a, Vec3d b, Vec3d c, Vec3d d, int axis) {
  const int o1 = orient2d(a, b, c, axis), o2 = orient2d(a, b, d, axis);
  const int o3 = orient2d(c, d, a, axis), o4 = orient2d(c, d, b, axis);
  if (o1 * o2 > 0 || o3 * o4 > 0) return false;
  if (o1 != 0 || o2 != 0) return true;
  // Collinear: overlap along the coordinate in which the line varies most.
  const Vec3d e = b - a;
  const double ex = std::abs(e.x), ey = std::abs(e.y), ez = std::abs(e.z);
  const auto coordinate = [&](Vec3d p) { return ex >= ey && ex >= ez ? p.x : ey >= ez ? p.y : p.z; };
  const double a1 = coordinate(a), b1 = coordinate(b), c1 = coordinate(c), d1 = coordinate(d);
  return std::min(a1, b1) <= std::max(c1, d1) && std::min(c1, d1) <= std::max(a1, b1);
}

// p in the closed triangle abc (not degenerate), all in one plane projected along `axis`.
bool inside_triangle_2d(Vec3d p, Vec3d a, Vec3d b, Vec3d c, int axis) {
  const int o1 = orient2d(a, b, p, axis), o2 = orient2d(b, c, p, axis), o3 = orient2d(c, a, p, axis);
  return !((o1 < 0 || o2 < 0 || o3 < 0) && (o1 > 0 || o2 > 0 || o3 > 0));
}

// The closed segment st meets the closed triangle abc (not degenerate), given the sides
// of abc's plane that s and t lie on (ds, dt: Plane::side).
bool segment_meets_triangle(Vec3d s, Vec3d t, int ds, int dt, const Plane& abc) {
  const Vec3d a = abc.a, b = abc.b, c = abc.c;
  if (ds * dt > 0) return false;
  if (ds == 0 && dt == 0) {
    const int axis = dominant_axis(a, b, c);
    return inside_triangle_2d(s, a, b, c, axis) || segments_meet_2d(s, t, a, b, axis) ||
           segments_meet_2d(s, t, b, c, axis) || segments_meet_2d(s, t, c, a, axis);
  }
  // Touching the plane at one end only: the segment meets the triangle there or not at
  // all. The line test below would decide it from the volumes of nearly flat tetrahedra,
  // whose signs are rounding noise when the segment lies almost in the plane (smooth
  // ribbons made of nearly coplanar quads); the projected test is well conditioned.
  if (ds == 0 || dt == 0) return inside_triangle_2d(ds == 0 ? s : t, a, b, c, dominant_axis(a, b, c));
  // The segment reaches the plane; it does so inside the triangle iff the line st passes
  // on the same side of (or through) all three edges.
  const int o1 = orient3d(s, t, a, b), o2 = orient3d(s, t, b, c), o3 = orient3d(s, t, c, a);
  return !((o1 < 0 || o2 < 0 || o3 < 0) && (o1 > 0 || o2 > 0 || o3 > 0));
}

// Two closed triangles with no vertex in common meet. Where they meet, the meeting set
// is convex and its extreme points lie on edges, so some edge of one meets the other:
// six segment tests after the cheap rejection by the planes.
bool triangles_meet(const std::array<Vec3d, 3>& t, const std::array<Vec3d, 3>& u) {
  const Plane pu(u[0], u[1], u[2]);
  const int a[3] = {pu.side(t[0]), pu.side(t[1]), pu.side(t[2])}; // t's corners against u's plane
  if (a[0] == a[1] && a[1] == a[2] && a[0] != 0) return false;
  const Plane pt(t[0], t[1], t[2]);
  const int b[3] = {pt.side(u[0]), pt.side(u[1]), pt.side(u[2])};
  if (b[0] == b[1] && b[1] == b[2] && b[0] != 0) return false;
  for (int k = 0; k < 3; ++k)
    if (segment_meets_triangle(t[k], t[(k + 1) % 3], a[k], a[(k + 1) % 3], pu) ||
        segment_meets_triangle(u[k], u[(k + 1) % 3], b[k], b[(k + 1) % 3], pt))
      return true;
  return false;
}

// Direction a - v lies in the closed wedge of triangle (v, c, d) at v, given the side of
// that triangle's plane a lies on (Plane::side).
bool in_wedge(Vec3d v, Vec3d a, int side, Vec3d c, Vec3d d) {
  if (side != 0) return false;
  const int axis = dominant_axis(v, c, d);
  const int s = orient2d(v, c, d, axis);
  return orient2d(v, c, a, axis) * s >= 0 && orient2d(v, a, d, axis) * s >= 0;
}

// Triangles (v, a, b) and (v, c, d) that share only v meet elsewhere. Near v each
// coincides with its wedge, so they meet beyond v iff an edge meets the other triangle
// away from v: the far edges ab and cd anywhere, an edge through v only when it lies in
// the other's plane and inside its wedge.
bool meet_beyond_vertex(Vec3d v, Vec3d a, Vec3d b, Vec3d c, Vec3d d) {
  // Usual on a smooth surface: one triangle lies strictly on one side of the other's
  // plane except at v, so they cannot meet elsewhere. One plane and two signs decide it.
  const Plane vab(v, a, b);
  const int sc = vab.side(c), sd = vab.side(d);
  if (sc * sd > 0) return false;
  const Plane vcd(v, c, d);
  const int sa = vcd.side(a), sb = vcd.side(b);
  if (sa * sb > 0) return false;
  return segment_meets_triangle(a, b, sa, sb, vcd) || segment_meets_triangle(c, d, sc, sd, vab) ||
         in_wedge(v, a, sa, c, d) || in_wedge(v, b, sb, c, d) || in_wedge(v, c, sc, a, b) || in_wedge(v, d, sd, a, b);
}

// Triangles (u, w, a) and (u, w, b) sharing the edge uw meet beyond it iff they fold
// onto each other: two planes through uw meet only in its line, so only coplanar
// triangles on the same side of uw overlap.
bool fold_over_edge(Vec3d u, Vec3d w, Vec3d a, Vec3d b) {
  if (orient3d(u, w, a, b) != 0) return false;
  const int axis = dominant_axis(u, w, a);
  return orient2d(u, w, a, axis) == orient2d(u, w, b, axis);
}

struct Triangles {
  std::vector<std::array<int32_t, 3>> corners;
  std::vector<int32_t> face; // the input polygon each triangle comes from
};

Triangles fan(const PolygonMesh& mesh) {
  Triangles t;
  const size_t count = size_t(std::max<int64_t>(0, int64_t(mesh.num_corners()) - 2 * int64_t(mesh.num_faces())));
  t.corners.reserve(count);
  t.face.reserve(count);
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> v = mesh.face(f);
    for (size_t k = 1; k + 1 < v.size(); ++k) {
      t.corners.push_back({v[0], v[k], v[k + 1]});
      t.face.push_back(f);
    }
  }
  return t;
}

// Whether triangles i and j (of different polygons, boxes overlapping) meet where the
// mesh does not join them.
bool intersect(const PolygonMesh& mesh, const Triangles& tris, int32_t i, int32_t j) {
  const std::array<int32_t, 3>& t = tris.corners[size_t(i)];
  const std::array<int32_t, 3>& u = tris.corners[size_t(j)];
  int shared = 0, ti[3], ui[3]; // positions in t and u of the shared vertices
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (t[a] == u[b]) {
        ti[shared] = a;
        ui[shared] = b;
        ++shared;
      }
  const auto p = [&](int32_t v) { return to_double(mesh.positions[size_t(v)]); };
  if (shared == 0)
    return triangles_meet({p(t[0]), p(t[1]), p(t[2])}, {p(u[0]), p(u[1]), p(u[2])});
  if (shared == 1) {
    const int a = ti[0], b = ui[0];
    return meet_beyond_vertex(p(t[a]), p(t[(a + 1) % 3]), p(t[(a + 2) % 3]), p(u[(b + 1) % 3]), p(u[(b + 2) % 3]));
  }
  if (shared == 2) {
    const int ta = 3 - ti[0] - ti[1], ua = 3 - ui[0] - ui[1]; // the unshared vertices
    return fold_over_edge(p(t[ti[0]]), p(t[ti[1]]), p(t[ta]), p(u[ua]));
  }
  return true; // the same three vertices: one lies on the other
}

bool degenerate(const PolygonMesh& mesh, const std::array<int32_t, 3>& t) {
  const Vec3d a = to_double(mesh.positions[size_t(t[0])]), b = to_double(mesh.positions[size_t(t[1])]),
           c = to_double(mesh.positions[size_t(t[2])]);
  const Vec3d n = cross(b - a, c - a);
  return n.x == 0 && n.y == 0 && n.z == 0;
}

// Which triangles have zero area: left out of the intersection search.
std::vector<uint8_t> degenerate_triangles(const PolygonMesh& mesh, const Triangles& tris) {
  std::vector<uint8_t> flags(tris.corners.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, flags.size(), 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) flags[i] = degenerate(mesh, tris.corners[i]);
  });
  return flags;
}

// A triangle's bounding box. Closed: boxes that touch overlap, so that touching
// triangles are tested.
struct Box {
  float lo[3] = {INFINITY, INFINITY, INFINITY};
  float hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  bool overlaps(const Box& b) const {
    return lo[0] <= b.hi[0] && b.lo[0] <= hi[0] && lo[1] <= b.hi[1] && b.lo[1] <= hi[1] && lo[2] <= b.hi[2] &&
           b.lo[2] <= hi[2];
  }
};

// The boxes of the triangles `which` of `tris`.
std::vector<Box> triangle_boxes(const PolygonMesh& mesh, const Triangles& tris, std::span<const int32_t> which) {
  std::vector<Box> boxes(which.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, boxes.size(), 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k)
      for (const int32_t v : tris.corners[size_t(which[k])]) {
        const Vec3 p = mesh.positions[size_t(v)];
        const float c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) {
          boxes[k].lo[a] = std::min(boxes[k].lo[a], c[a]);
          boxes[k].hi[a] = std::max(boxes[k].hi[a], c[a]);
        }
      }
  });
  return boxes;
}

// Embree's collision query finds the candidate pairs: a scene holds one user geometry
// whose primitives are boxes (rtcCollide takes nothing else), and `boxes` must outlive
// the scene's commit, which reads them.
void add_boxes(EmbreeScene& scene, std::span<const Box> boxes) {
  RTCGeometry geometry = rtcNewGeometry(scene.device(), RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, unsigned(boxes.size()));
  rtcSetGeometryUserData(geometry, const_cast<Box*>(boxes.data()));
  rtcSetGeometryBoundsFunction(
      geometry,
      [](const RTCBoundsFunctionArguments* args) {
        // Embree leaves out boxes beyond about 1.8e18; clamping keeps every overlap.
        const auto clamp = [](float x) { return std::clamp(x, -1e18f, 1e18f); };
        const Box& b = static_cast<const Box*>(args->geometryUserPtr)[args->primID];
        *args->bounds_o = {clamp(b.lo[0]), clamp(b.lo[1]), clamp(b.lo[2]), 0, clamp(b.hi[0]), clamp(b.hi[1]), clamp(b.hi[2]), 0};
      },
      nullptr);
  scene.attach(geometry);
  scene.commit();
}

// Calls f(i, j) for every box i of `a` and j of `b` that overlap, from several threads at
// once and in no particular order. Embree pairs whole leaves of its two trees, so the
// boxes are compared here. With a and b the same scene each unordered pair comes once,
// as i < j (Embree meets it in both orders).
template <class F>
void for_each_overlapping(const EmbreeScene& a, std::span<const Box> boxes_a, const EmbreeScene& b,
                          std::span<const Box> boxes_b, F&& f) {
  const bool self = &a == &b;
  auto candidate = [&](unsigned i, unsigned j) {
    if ((!self || i < j) && boxes_a[i].overlaps(boxes_b[j])) f(int32_t(i), int32_t(j));
  };
  using Candidate = decltype(candidate);
  rtcCollide(
      a.scene(), b.scene(),
      [](void* user, RTCCollision* pairs, unsigned count) {
        for (unsigned k = 0; k < count; ++k) (*static_cast<Candidate*>(user))(pairs[k].primID0, pairs[k].primID1);
      },
      &candidate);
  a.throw_if_failed();
}

// Calls f(i, j), i < j, for every pair of triangles whose boxes overlap, as for_each_overlapping.
// With a progress, the boxes are met a block at a time against all of them, its fraction
// advanced and its cancel seen after each block: a wire much thicker than the gaps of its
// curve has billions of pairs (minutes), and Embree's query cannot be stopped midway.
template <class F>
void for_each_overlapping_pair(const PolygonMesh& mesh, const Triangles& tris, Progress* progress, F&& f) {
  if (tris.corners.empty()) return;
  std::vector<int32_t> all(tris.corners.size());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<Box> boxes = triangle_boxes(mesh, tris, all);
  // A few triangles: every pair, cheaper than building any tree.
  if (constexpr size_t few = 16; boxes.size() <= few) {
    for (size_t i = 0; i < boxes.size(); ++i)
      for (size_t j = i + 1; j < boxes.size(); ++j)
        if (boxes[i].overlaps(boxes[j])) f(int32_t(i), int32_t(j));
    return;
  }
  EmbreeScene scene("printability", RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_LOW);
  add_boxes(scene, boxes);
  if (!progress) return for_each_overlapping(scene, boxes, scene, boxes, f);
  constexpr size_t block = 8192;
  for (size_t first = 0; first < boxes.size(); first += block) {
    progress->advance(double(first) / double(boxes.size()));
    const std::span<const Box> part(boxes.data() + first, std::min(block, boxes.size() - first));
    EmbreeScene part_scene("printability", RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_LOW);
    add_boxes(part_scene, part);
    for_each_overlapping(part_scene, part, scene, boxes, [&](int32_t i, int32_t j) {
      if (int32_t(first) + i < j) f(int32_t(first) + i, j);
    });
  }
}

// The first intersecting pair in the order of PrintabilityReport::first_intersection:
// the least (i, j), i < j, in lexicographic order. Pairs are met in parallel in any
// order; each one not below the best found so far is dismissed untested, and the best
// only ever decreases, so the answer is that least pair whatever the timing.
std::array<int32_t, 2> first_intersecting_pair(const PolygonMesh& mesh, const Triangles& tris,
                                               const std::vector<uint8_t>& skip, Progress* progress) {
  const auto key = [](int32_t i, int32_t j) { return uint64_t(uint32_t(i)) << 32 | uint32_t(j); };
  constexpr uint64_t none = std::numeric_limits<uint64_t>::max();
  std::atomic<uint64_t> best{none};
  for_each_overlapping_pair(mesh, tris, progress, [&](int32_t i, int32_t j) {
    const uint64_t k = key(i, j);
    if (k >= best.load(std::memory_order_relaxed) || skip[size_t(i)] || skip[size_t(j)] ||
        tris.face[size_t(i)] == tris.face[size_t(j)] || !intersect(mesh, tris, i, j))
      return;
    uint64_t current = best.load();
    while (k < current && !best.compare_exchange_weak(current, k)) {
    }
  });
  const uint64_t first = best.load();
  if (first == none) return {-1, -1};
  return {tris.face[size_t(first >> 32)], tris.face[size_t(first & 0xffffffffu)]};
}

// Marks in `hit` both triangles of every intersecting pair.
void mark_intersecting(const PolygonMesh& mesh, const Triangles& tris, const std::vector<uint8_t>& skip,
                       std::vector<uint8_t>& hit, Progress* progress) {
  for_each_overlapping_pair(mesh, tris, progress, [&](int32_t i, int32_t j) {
    if (skip[size_t(i)] || skip[size_t(j)] || tris.face[size_t(i)] == tris.face[size_t(j)]) return;
    // Threads share the flags; any of them writes only 1, so relaxed order is enough.
    std::atomic_ref<uint8_t> hit_i(hit[size_t(i)]), hit_j(hit[size_t(j)]);
    if (hit_i.load(std::memory_order_relaxed) && hit_j.load(std::memory_order_relaxed)) return; // nothing to learn
    if (!intersect(mesh, tris, i, j)) return;
    hit_i.store(1, std::memory_order_relaxed);
    hit_j.store(1, std::memory_order_relaxed);
  });
}

// Fills report.components and report.volume from inspect()'s components: the
// connectivity they need is built once, there.
void measure_components(const PolygonMesh& mesh, const Triangles& tris, const MeshReport& topology,
                        PrintabilityReport& report) {
  std::vector<SolidComponent>& components = report.components;
  components.reserve(topology.components.size());
  for (const ComponentReport& k : topology.components)
    components.push_back({.faces = k.faces,
                          .euler_characteristic = k.euler_characteristic,
                          .genus = k.genus,
                          .closed = k.boundary_loops == 0});

  // Volume: the divergence theorem over the fan triangles, each the signed volume of its
  // tetrahedron with the origin. Relative to a point near the mesh (the box's centre) to
  // keep the terms small when the model sits far from the origin.
  const Box3& box = report.bounding_box;
  const Vec3d centre = box.empty() ? Vec3d{0, 0, 0} : to_double((box.min + box.max) * 0.5f);
  for (size_t i = 0; i < tris.corners.size(); ++i) {
    const int32_t k = topology.face_components[size_t(tris.face[i])];
    if (k < 0) continue;
    const std::array<int32_t, 3>& t = tris.corners[i];
    const Vec3d a = to_double(mesh.positions[size_t(t[0])]) - centre, b = to_double(mesh.positions[size_t(t[1])]) - centre,
             cc = to_double(mesh.positions[size_t(t[2])]) - centre;
    components[size_t(k)].volume += dot(a, cross(b, cc)) / 6;
  }
  for (const SolidComponent& k : components) report.volume += k.volume;
}

// Embree's ray context with what its filter needs to leave out the triangles around the
// vertex a ray starts from (Embree passes the context on to the filter).
struct VertexRayContext {
  RTCIntersectContext context;
  const std::array<int32_t, 3>* corners;
  int32_t vertex;
};

void skip_triangles_around_vertex(const RTCFilterFunctionNArguments* args) {
  const auto* c = reinterpret_cast<const VertexRayContext*>(args->context);
  for (unsigned k = 0; k < args->N; ++k) {
    if (args->valid[k] == 0) continue;
    const std::array<int32_t, 3>& t = c->corners[RTCHitN_primID(args->hit, args->N, k)];
    if (t[0] == c->vertex || t[1] == c->vertex || t[2] == c->vertex) args->valid[k] = 0;
  }
}

// `inward` per face: -1 to cast against the normals (a component of positive volume),
// +1 along them (one turned inside out), 0 to cast no ray from its vertices. Embree
// finds the nearest triangle hit in float, in its robust mode, so that rays through
// edges and vertices are not lost. The float distance is kept as it is: it does not
// depend on which of several triangles tied at it Embree's tree reports, so the result
// does not depend on the number of threads the tree was built with.
void min_thickness(const PolygonMesh& mesh, const Triangles& tris, const std::vector<int8_t>& inward, bool gaps,
                   std::span<const uint8_t> unmeasured, PrintabilityReport& report, Progress* progress) {
  const int32_t nv = mesh.num_vertices();
  // Float, and no per-vertex result kept (a reduction instead): on large meshes the
  // cost is mostly in touching fresh memory.
  std::vector<Vec3> normal(size_t(nv), Vec3{0, 0, 0});
  std::vector<int8_t> vertex_side(size_t(nv), 0);
  // The corner angles (three atan2 a triangle, most of this loop's time) in parallel, a
  // block at a time; the sums in triangle order on one thread, so that they round as a
  // single pass would, whatever the threads.
  constexpr size_t block = size_t(1) << 16;
  std::vector<std::array<Vec3, 3>> weighted(std::min(block, tris.corners.size()));
  std::vector<uint8_t> flat(weighted.size());
  for (size_t first = 0; first < tris.corners.size(); first += block) {
    const size_t count = std::min(block, tris.corners.size() - first);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1024), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t j = r.begin(); j < r.end(); ++j) {
        const std::array<int32_t, 3>& t = tris.corners[first + j];
        const Vec3d corner[3] = {to_double(mesh.positions[size_t(t[0])]), to_double(mesh.positions[size_t(t[1])]),
                              to_double(mesh.positions[size_t(t[2])])};
        Vec3d n = cross(corner[1] - corner[0], corner[2] - corner[0]);
        const double length = norm(n);
        flat[j] = length == 0;
        if (flat[j]) continue;
        n = {n.x / length, n.y / length, n.z / length};
        // Weighted by the corner angle, so that the normal does not depend on how the
        // faces around the vertex are triangulated (a cube's corner gets its diagonal).
        for (int k = 0; k < 3; ++k) {
          const Vec3d e1 = corner[(k + 1) % 3] - corner[k], e2 = corner[(k + 2) % 3] - corner[k];
          const double angle = std::atan2(norm(cross(e1, e2)), dot(e1, e2));
          weighted[j][size_t(k)] = Vec3{float(angle * n.x), float(angle * n.y), float(angle * n.z)};
        }
      }
    });
    for (size_t j = 0; j < count; ++j) {
      if (flat[j]) continue;
      const std::array<int32_t, 3>& t = tris.corners[first + j];
      for (int k = 0; k < 3; ++k) {
        Vec3& s = normal[size_t(t[size_t(k)])];
        s = s + weighted[j][size_t(k)];
        vertex_side[size_t(t[size_t(k)])] = inward[size_t(tris.face[first + j])];
      }
    }
  }

  // A quick build and a compact tree: on millions of triangles building the tree (and
  // touching its fresh memory) costs more than the one ray per vertex it serves.
  EmbreeScene scene("printability", RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT, RTC_BUILD_QUALITY_LOW);
  RTCGeometry geometry = rtcNewGeometry(scene.device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  set_vertices(geometry, mesh.positions);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tris.corners.data(), 0,
                             sizeof(std::array<int32_t, 3>), tris.corners.size());
  rtcSetGeometryIntersectFilterFunction(geometry, skip_triangles_around_vertex);
  scene.attach(geometry);
  scene.commit();

  // The rays in the order their vertices first appear among the triangles, so that
  // consecutive rays start near each other and walk the same parts of the tree
  // (a subdivided mesh numbers its vertices by kind, not by place).
  std::vector<int32_t> order;
  order.reserve(size_t(nv));
  {
    std::vector<uint8_t> listed(size_t(nv), 0);
    for (const std::array<int32_t, 3>& t : tris.corners)
      for (const int32_t v : t)
        if (!listed[size_t(v)]) {
          listed[size_t(v)] = 1;
          order.push_back(v);
        }
  }
  // The least (distance, vertex) inward and outward: the same whatever the order and the
  // split into tasks.
  using Least = std::pair<double, int32_t>;
  using Both = std::array<Least, 2>;
  const Both least = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, order.size(), 1024), Both{Least{INFINITY, -1}, Least{INFINITY, -1}},
      [&](const tbb::blocked_range<size_t>& r, Both best) {
        check_progress(progress);
        VertexRayContext context;
        rtcInitIntersectContext(&context.context);
        context.corners = tris.corners.data();
        for (size_t i = r.begin(); i < r.end(); ++i) {
          const int32_t v = order[i];
          const int32_t side = vertex_side[size_t(v)];
          const Vec3 n = normal[size_t(v)];
          const double length = std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z);
          if (side == 0 || length == 0 || (!unmeasured.empty() && unmeasured[size_t(v)])) continue;
          const Vec3 origin = mesh.positions[size_t(v)];
          context.vertex = v;
          for (int way = 0; way < (gaps ? 2 : 1); ++way) {
            const double scale = (way == 0 ? side : -side) / length;
            RTCRayHit rh{};
            rh.ray.org_x = origin.x;
            rh.ray.org_y = origin.y;
            rh.ray.org_z = origin.z;
            rh.ray.dir_x = float(n.x * scale);
            rh.ray.dir_y = float(n.y * scale);
            rh.ray.dir_z = float(n.z * scale);
            rh.ray.tnear = 0;
            rh.ray.tfar = INFINITY;
            rh.ray.mask = 0xffffffffu;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene.scene(), &context.context, &rh);
            if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
              best[size_t(way)] = std::min(best[size_t(way)], Least{double(rh.ray.tfar), v});
          }
        }
        return best;
      },
      [](const Both& a, const Both& b) { return Both{std::min(a[0], b[0]), std::min(a[1], b[1])}; });
  report.min_thickness = least[0].first;
  report.thinnest_vertex = std::isfinite(least[0].first) ? least[0].second : -1;
  if (!gaps) return;
  report.gaps_checked = true;
  report.min_gap = least[1].first;
  report.narrowest_vertex = std::isfinite(least[1].first) ? least[1].second : -1;
}

} // namespace

bool PrintabilityReport::too_thin() const {
  return required_thickness > 0 && !(thickness_checked && min_thickness >= required_thickness);
}

bool PrintabilityReport::too_close() const {
  return required_gap > 0 && !(gaps_checked && min_gap >= required_gap);
}

bool PrintabilityReport::printable() const {
  return watertight && !self_intersecting && !too_thin() && !too_close() &&
         std::all_of(components.begin(), components.end(), [](const SolidComponent& k) { return k.volume > 0; });
}

PrintabilityReport check_printability(const PolygonMesh& mesh, const PrintabilityOptions& options, Progress* progress) {
  const MeshReport topology = inspect(mesh);
  if (topology.out_of_range_indices > 0)
    throw InputError("mesh has " + std::to_string(topology.out_of_range_indices) + " face indices out of range");
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    for (const int32_t v : mesh.face(f))
      if (!is_finite(mesh.positions[size_t(v)]))
        throw InputError("mesh: vertex " + std::to_string(v) + " (used by face " + std::to_string(f) +
                         ") has a non-finite position");
  if (!options.unmeasured.empty() && options.unmeasured.size() != mesh.positions.size())
    throw UsageError("unmeasured: expected one flag per vertex (" + std::to_string(mesh.positions.size()) + "), got " +
                     std::to_string(options.unmeasured.size()));
  if (!(options.required_thickness >= 0) || !std::isfinite(options.required_thickness))
    throw UsageError("required thickness " + std::to_string(options.required_thickness) +
                     ": expected a finite number, 0 or more");
  PrintabilityReport report;
  report.required_thickness = options.required_thickness;
  report.required_gap = options.required_gap;
  report.nozzle = options.nozzle;
  report.vertices = mesh.num_vertices();
  report.faces = mesh.num_faces();
  report.boundary_edges = topology.boundary_edges;
  report.non_manifold_edges = topology.non_manifold_edges;
  report.non_manifold_vertices = topology.non_manifold_vertices;
  report.misoriented_edges = topology.misoriented_edges;
  report.orientable = topology.orientable;
  report.bounding_box = topology.bounding_box;
  report.watertight = mesh.num_faces() > 0 && topology.boundary_edges == 0 && topology.non_manifold_edges == 0 &&
                      topology.non_manifold_vertices == 0 && topology.misoriented_edges == 0 &&
                      topology.orientable && topology.degenerate_faces == 0;

  const Triangles tris = fan(mesh);
  report.triangles = int64_t(tris.corners.size());
  measure_components(mesh, tris, topology, report);

  const std::vector<uint8_t> skip = degenerate_triangles(mesh, tris);
  report.degenerate_triangles = int32_t(std::count(skip.begin(), skip.end(), 1));
  if (!options.self_intersections && !options.thickness) return report;

  if (options.self_intersections && options.known_clear) {
    report.self_intersections_checked = true;
  } else if (options.self_intersections) {
    report.self_intersections_checked = true;
    report.first_intersection = first_intersecting_pair(mesh, tris, skip, progress);
    report.self_intersecting = report.first_intersection[0] >= 0;
  }
  if (options.thickness && report.boundary_edges == 0 && !report.components.empty()) {
    report.thickness_checked = true;
    std::vector<int8_t> inward(size_t(mesh.num_faces()), 0);
    for (int32_t f = 0; f < mesh.num_faces(); ++f)
      if (const int32_t k = topology.face_components[size_t(f)]; k >= 0) inward[size_t(f)] = int8_t(-sign(report.components[size_t(k)].volume));
    min_thickness(mesh, tris, inward, options.nozzle > 0, options.unmeasured, report, progress);
    if (options.nozzle > 0 && !report.bounding_box.empty()) {
      // Scaling the whole mesh scales both; the larger of the two factors does.
      const double factor = std::max(2 * options.nozzle / report.min_thickness, options.nozzle / report.min_gap);
      if (factor > 0) report.smallest_size = factor * report.bounding_box.largest_side(); // 0: no ray hit anything
    }
  }
  return report;
}

std::vector<int32_t> self_intersecting_faces(const PolygonMesh& mesh, std::span<const uint8_t> among, Progress* progress) {
  const Triangles tris = fan(mesh);
  const std::vector<uint8_t> skip = degenerate_triangles(mesh, tris);
  std::vector<uint8_t> hit(tris.corners.size());
  if (among.empty()) {
    mark_intersecting(mesh, tris, skip, hit, progress);
  } else {
    // The chosen faces' triangles against all: a pair of two chosen triangles is tested
    // from the lower one.
    std::vector<int32_t> chosen, tested;
    for (size_t i = 0; i < tris.corners.size(); ++i)
      if (!skip[i]) {
        tested.push_back(int32_t(i));
        if (among[size_t(tris.face[i])]) chosen.push_back(int32_t(i));
      }
    if (!chosen.empty()) {
      const std::vector<Box> tested_boxes = triangle_boxes(mesh, tris, tested), chosen_boxes = triangle_boxes(mesh, tris, chosen);
      EmbreeScene tested_scene("printability", RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_LOW);
      EmbreeScene chosen_scene("printability", RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_LOW);
      add_boxes(tested_scene, tested_boxes);
      add_boxes(chosen_scene, chosen_boxes);
      for_each_overlapping(tested_scene, tested_boxes, chosen_scene, chosen_boxes, [&](int32_t a, int32_t k) {
        const size_t i = size_t(tested[size_t(a)]), j = size_t(chosen[size_t(k)]);
        if ((among[size_t(tris.face[i])] && j <= i) || tris.face[i] == tris.face[j] || !intersect(mesh, tris, int32_t(i), int32_t(j)))
          return;
        std::atomic_ref<uint8_t>(hit[i]).store(1, std::memory_order_relaxed);
        std::atomic_ref<uint8_t>(hit[j]).store(1, std::memory_order_relaxed);
      });
    }
  }
  std::vector<int32_t> faces;
  for (size_t i = 0; i < hit.size(); ++i)
    if (hit[i] && (faces.empty() || faces.back() != tris.face[i])) faces.push_back(tris.face[i]);
  return faces;
}

std::string printability_json(const PrintabilityReport& r) {
  using Json = nlohmann::ordered_json;
  const auto finite_or_null = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  const auto point = [](Vec3 p) { return Json::array({p.x, p.y, p.z}); };
  Json j;
  j["printable"] = r.printable();
  j["vertices"] = r.vertices;
  j["faces"] = r.faces;
  j["triangles"] = r.triangles;
  j["degenerate_triangles"] = r.degenerate_triangles;
  j["watertight"] = r.watertight;
  j["boundary_edges"] = r.boundary_edges;
  j["non_manifold_edges"] = r.non_manifold_edges;
  j["non_manifold_vertices"] = r.non_manifold_vertices;
  j["misoriented_edges"] = r.misoriented_edges;
  j["orientable"] = r.orientable;
  j["volume"] = r.volume;
  j["self_intersecting"] = r.self_intersections_checked ? Json(r.self_intersecting) : Json(nullptr);
  j["first_intersection"] =
      r.self_intersecting ? Json::array({r.first_intersection[0], r.first_intersection[1]}) : Json(nullptr);
  j["min_thickness"] = r.thickness_checked ? finite_or_null(r.min_thickness) : Json(nullptr);
  j["thinnest_vertex"] = r.thinnest_vertex >= 0 ? Json(r.thinnest_vertex) : Json(nullptr);
  j["required_thickness"] = r.required_thickness > 0 ? Json(r.required_thickness) : Json(nullptr);
  j["too_thin"] = r.required_thickness > 0 ? Json(r.too_thin()) : Json(nullptr);
  if (r.gaps_checked) {
    j["min_gap"] = finite_or_null(r.min_gap);
    j["narrowest_vertex"] = r.narrowest_vertex >= 0 ? Json(r.narrowest_vertex) : Json(nullptr);
    j["required_gap"] = r.required_gap > 0 ? Json(r.required_gap) : Json(nullptr);
    j["too_close"] = r.required_gap > 0 ? Json(r.too_close()) : Json(nullptr);
    j["nozzle"] = r.nozzle;
    j["smallest_printable_size"] = finite_or_null(r.smallest_size);
  }
  j["bounding_box"] = r.bounding_box.empty() ? Json(nullptr)
                                             : Json{{"min", point(r.bounding_box.min)}, {"max", point(r.bounding_box.max)}};
  Json components = Json::array();
  for (const SolidComponent& k : r.components)
    components.push_back({{"faces", k.faces},
                          {"euler_characteristic", k.euler_characteristic},
                          {"closed", k.closed},
                          {"volume", k.volume}});
  j["components"] = components;
  return j.dump(2);
}

namespace {

// Up to three significant digits, so that the printed factor is never short of x.
double round_up(double x) {
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2);
  return std::ceil(x / unit) * unit;
}

} // namespace

std::string printability_summary(const PrintabilityReport& r) {
  char text[256];
  std::string s = std::to_string(r.triangles) + (r.triangles == 1 ? " triangle, " : " triangles, ");
  if (r.watertight) {
    s += "watertight";
  } else {
    std::string problems;
    const auto add = [&](int64_t n, const char* what) {
      if (n > 0) problems += (problems.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    add(r.boundary_edges, "boundary edges");
    add(r.non_manifold_edges, "non-manifold edges");
    add(r.non_manifold_vertices, "non-manifold vertices");
    add(r.misoriented_edges, "misoriented edges");
    if (!r.orientable) problems += std::string(problems.empty() ? "" : ", ") + "not orientable";
    s += "not watertight" + (problems.empty() ? std::string() : " (" + problems + ")");
  }
  s += ", " + std::to_string(r.components.size()) + (r.components.size() == 1 ? " component" : " components");
  if (!r.components.empty()) {
    s += " (Euler characteristic";
    for (size_t k = 0; k < r.components.size() && k < 8; ++k) {
      s += ' ';
      s += std::to_string(r.components[k].euler_characteristic);
    }
    s += r.components.size() > 8 ? " ...)" : ")";
  }
  const bool outward = std::all_of(r.components.begin(), r.components.end(), [](const SolidComponent& k) { return k.volume > 0; });
  std::snprintf(text, sizeof text, ", volume %.6g (%s)", r.volume, outward ? "outward" : "some component inside out or empty");
  s += text;
  if (!r.self_intersections_checked) s += ", self-intersection not checked";
  else if (!r.self_intersecting) s += ", no self-intersection";
  else
    s += ", self-intersecting (first: faces " + std::to_string(r.first_intersection[0]) + " and " +
         std::to_string(r.first_intersection[1]) + ")";
  if (!r.thickness_checked) {
    s += ", thickness not measured (open mesh)";
  } else if (std::isfinite(r.min_thickness)) {
    std::snprintf(text, sizeof text, ", minimum thickness %.4g (at vertex %d)", r.min_thickness, r.thinnest_vertex);
    s += text;
  }
  if (r.required_thickness > 0) {
    if (!r.thickness_checked)
      std::snprintf(text, sizeof text, ", so not known to be %.4g thick as required", r.required_thickness);
    else if (r.too_thin()) // scaling the whole model is the one change that always thickens it enough
      std::snprintf(text, sizeof text, ", thinner than the %.4g required (scaled by %.3g it would do)", r.required_thickness,
                    round_up(r.required_thickness / r.min_thickness));
    else
      std::snprintf(text, sizeof text, ", at least the %.4g required", r.required_thickness);
    s += text;
  }
  if (r.gaps_checked) {
    if (std::isfinite(r.min_gap)) {
      std::snprintf(text, sizeof text, ", narrowest gap %.4g (at vertex %d)", r.min_gap, r.narrowest_vertex);
      s += text;
    }
    if (r.required_gap > 0) {
      std::snprintf(text, sizeof text, r.too_close() ? ", narrower than the %.4g required" : ", at least the %.4g required",
                    r.required_gap);
      s += text;
    }
    if (std::isfinite(r.smallest_size)) {
      std::snprintf(text, sizeof text, ", prints with a %.4g mm nozzle from %.4g mm on its largest side", r.nozzle,
                    round_up(r.smallest_size));
      s += text;
    }
  }
  if (!r.bounding_box.empty()) {
    const Box3& b = r.bounding_box;
    std::snprintf(text, sizeof text, ", bounding box %.4g x %.4g x %.4g from (%.4g, %.4g, %.4g)", double(b.max.x - b.min.x),
                  double(b.max.y - b.min.y), double(b.max.z - b.min.z), double(b.min.x), double(b.min.y),
                  double(b.min.z));
    s += text;
  }
  s += r.printable() ? ": printable." : ": not printable.";
  return s;
}

} // namespace meander
