#include "meander/flip_caps.h"

#include "meander/connectivity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <unordered_set>

namespace meander {

namespace {

// The cosine of the angle at corner o of triangle (o, p, q); 1 when a side has no length,
// so that a triangle with coincident corners is never taken for a cap.
double corner_cosine(Vec3 o, Vec3 p, Vec3 q) {
  const double lp = norm(p - o), lq = norm(q - o);
  return lp > 0 && lq > 0 ? dot(p - o, q - o) / (lp * lq) : 1.0;
}

// The cosine of the largest angle of triangle (a, b, c): the smallest of the three.
double largest_angle_cosine(Vec3 a, Vec3 b, Vec3 c) {
  return std::min({corner_cosine(a, b, c), corner_cosine(b, c, a), corner_cosine(c, a, b)});
}


bool has_edge(const Connectivity& c, int32_t u, int32_t v) {
  const std::array<int32_t, 2> key{std::min(u, v), std::max(u, v)};
  return std::binary_search(c.edge_vertices.begin(), c.edge_vertices.end(), key);
}

// One pass over the edges in order; each face flips at most once, so every flip reads
// the faces as the connectivity saw them.
int64_t flip_pass(PolygonMesh& mesh, const CapFlipOptions& options) {
  const Connectivity c = build_connectivity(mesh);
  const double cap_cosine = std::cos(options.cap_angle_degrees * std::numbers::pi / 180);
  std::vector<uint8_t> flipped(size_t(mesh.num_faces()), 0);
  std::unordered_set<uint64_t> made; // edges this pass made, which `c` does not know
  int64_t flips = 0;
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    if (c.edge_degree(e) != 2) continue;
    const int32_t h1 = c.halfedges(e)[0], h2 = c.halfedges(e)[1];
    const int32_t f1 = c.halfedge_face[size_t(h1)], f2 = c.halfedge_face[size_t(h2)];
    if (mesh.face_size(f1) != 3 || mesh.face_size(f2) != 3 || flipped[size_t(f1)] || flipped[size_t(f2)]) continue;
    const int32_t a = mesh.face_vertices[size_t(h1)], b = halfedge_target(mesh, c, h1);
    if (mesh.face_vertices[size_t(h2)] != b || halfedge_target(mesh, c, h2) != a) continue; // misoriented pair
    const int32_t cv = halfedge_target(mesh, c, next_halfedge(mesh, c, h1));
    const int32_t dv = halfedge_target(mesh, c, next_halfedge(mesh, c, h2));
    if (cv == dv) continue;
    const auto at = [&](int32_t v) { return mesh.positions[size_t(v)]; };
    const Vec3 pa = at(a), pb = at(b), pc = at(cv), pd = at(dv);
    // The cap's largest angle must face the shared edge, or the flip does not touch it.
    const double at_c = corner_cosine(pc, pa, pb), at_d = corner_cosine(pd, pb, pa);
    if (std::min(at_c, at_d) >= cap_cosine) continue;
    const double before = std::min(largest_angle_cosine(pa, pb, pc), largest_angle_cosine(pb, pa, pd));
    if (std::min(at_c, at_d) > before) continue;
    const double after = std::min(largest_angle_cosine(pa, pd, pc), largest_angle_cosine(pd, pb, pc));
    if (!(after > before)) continue;
    // The flip swaps two faces of the tetrahedron (a, b, c, d) for the other two: the
    // surface moves by the distance between the lines a-b and c-d, its height over them.
    const Vec3 ab = pb - pa, cd = pd - pc;
    const double move = std::abs(dot(ab, cross(pc - pa, pd - pa))) / norm(cross(ab, cd));
    if (!(move <= options.max_move * norm(ab))) continue;
    const Vec3 facing = cross(ab, pc - pa) + cross(pa - pb, pd - pb);
    if (!(dot(cross(pd - pa, pc - pa), facing) > 0 && dot(cross(pb - pd, pc - pd), facing) > 0)) continue;
    const uint64_t key = uint64_t(uint32_t(std::min(cv, dv))) << 32 | uint32_t(std::max(cv, dv));
    if (has_edge(c, cv, dv) || made.contains(key)) continue;
    made.insert(key);
    int32_t* t1 = mesh.face_vertices.data() + mesh.face_start[size_t(f1)];
    int32_t* t2 = mesh.face_vertices.data() + mesh.face_start[size_t(f2)];
    t1[0] = a, t1[1] = dv, t1[2] = cv;
    t2[0] = dv, t2[1] = b, t2[2] = cv;
    flipped[size_t(f1)] = flipped[size_t(f2)] = 1;
    ++flips;
  }
  return flips;
}

} // namespace

CapFlips flip_caps(PolygonMesh mesh, const CapFlipOptions& options) {
  CapFlips result;
  for (int pass = 0; pass < options.max_passes; ++pass) {
    const int64_t flips = flip_pass(mesh, options);
    result.flips += flips;
    if (flips == 0) break;
  }
  result.mesh = std::move(mesh);
  return result;
}

} // namespace meander
