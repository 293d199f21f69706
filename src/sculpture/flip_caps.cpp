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

class FlipPass {
public:
  FlipPass(PolygonMesh& mesh, const CapFlipOptions& options)
      : mesh_(mesh), c_(build_connectivity(mesh)), options_(options),
        cap_cosine_(std::cos(options.cap_angle_degrees * std::numbers::pi / 180)),
        touched_(size_t(mesh.num_faces()), 0), on_boundary_(size_t(mesh.num_vertices()), 0) {
    for (int32_t e = 0; e < c_.num_edges(); ++e)
      if (c_.edge_degree(e) == 1)
        for (int32_t v : c_.edge_vertices[size_t(e)]) on_boundary_[size_t(v)] = 1;
  }

  // One pass over the edges in order; each face changes at most once, so every change
  // reads the faces as the connectivity saw them.
  CapFlips run() {
    CapFlips counts;
    for (int32_t e = 0; e < c_.num_edges(); ++e) {
      if (c_.edge_degree(e) == 2) counts.flips += flip(c_.halfedges(e)[0], c_.halfedges(e)[1]);
      else if (c_.edge_degree(e) == 1) counts.cuts += cut(c_.halfedges(e)[0]);
    }
    if (counts.cuts > 0) remove_cut_faces();
    return counts;
  }

private:
  Vec3 at(int32_t v) const { return mesh_.positions[size_t(v)]; }
  int32_t target(int32_t h) const { return halfedge_target(mesh_, c_, h); }
  int32_t opposite(int32_t h) const { return target(next_halfedge(mesh_, c_, h)); }
  bool free_triangle(int32_t f) const { return mesh_.face_size(f) == 3 && !touched_[size_t(f)]; }

  bool flip(int32_t h1, int32_t h2) {
    const int32_t f1 = c_.face_of(h1), f2 = c_.face_of(h2);
    if (!free_triangle(f1) || !free_triangle(f2)) return false;
    const int32_t a = mesh_.face_vertices[size_t(h1)], b = target(h1);
    if (mesh_.face_vertices[size_t(h2)] != b || target(h2) != a) return false; // misoriented pair
    const int32_t cv = opposite(h1), dv = opposite(h2);
    if (cv == dv) return false;
    const Vec3 pa = at(a), pb = at(b), pc = at(cv), pd = at(dv);
    // The cap's largest angle must face the shared edge, or the flip does not touch it.
    const double at_c = corner_cosine(pc, pa, pb), at_d = corner_cosine(pd, pb, pa);
    if (std::min(at_c, at_d) >= cap_cosine_) return false;
    const double before = std::min(largest_angle_cosine(pa, pb, pc), largest_angle_cosine(pb, pa, pd));
    if (std::min(at_c, at_d) > before) return false;
    const double after = std::min(largest_angle_cosine(pa, pd, pc), largest_angle_cosine(pd, pb, pc));
    if (!(after > before)) return false;
    // The flip swaps two faces of the tetrahedron (a, b, c, d) for the other two: the
    // surface moves by the distance between the lines a-b and c-d, its height over them.
    const Vec3 ab = pb - pa, cd = pd - pc;
    const double move = std::abs(dot(ab, cross(pc - pa, pd - pa))) / norm(cross(ab, cd));
    if (!(move <= options_.max_move * norm(ab))) return false;
    const Vec3 facing = cross(ab, pc - pa) + cross(pa - pb, pd - pb);
    if (!(dot(cross(pd - pa, pc - pa), facing) > 0 && dot(cross(pb - pd, pc - pd), facing) > 0)) return false;
    const uint64_t key = uint64_t(uint32_t(std::min(cv, dv))) << 32 | uint32_t(std::max(cv, dv));
    if (has_edge(c_, cv, dv) || made_.contains(key)) return false;
    made_.insert(key);
    int32_t* t1 = mesh_.face_vertices.data() + mesh_.face_start[size_t(f1)];
    int32_t* t2 = mesh_.face_vertices.data() + mesh_.face_start[size_t(f2)];
    t1[0] = a, t1[1] = dv, t1[2] = cv;
    t2[0] = dv, t2[1] = b, t2[2] = cv;
    touched_[size_t(f1)] = touched_[size_t(f2)] = 1;
    return true;
  }

  // A cap whose long edge lies on the boundary has no edge to flip: it is cut off, so the
  // boundary runs through its apex, when that moves the surface as little as a flip may.
  // The apex must be inside the surface, or it would join two boundary fans (a
  // non-manifold vertex); then the cap's other two edges are inside too.
  bool cut(int32_t h) {
    const int32_t f = c_.face_of(h);
    if (!free_triangle(f)) return false;
    const int32_t a = mesh_.face_vertices[size_t(h)], b = target(h), cv = opposite(h);
    if (on_boundary_[size_t(cv)]) return false;
    const Vec3 pa = at(a), pb = at(b), pc = at(cv);
    if (corner_cosine(pc, pa, pb) >= cap_cosine_) return false;
    const Vec3 ab = pb - pa;
    const double height = norm(cross(ab, pc - pa)) / norm(ab);
    if (!(height <= options_.max_move * norm(ab))) return false;
    touched_[size_t(f)] = 2;
    on_boundary_[size_t(cv)] = 1;
    return true;
  }

  void remove_cut_faces() {
    std::vector<uint8_t> cut(touched_.size());
    for (size_t f = 0; f < cut.size(); ++f) cut[f] = touched_[f] == 2;
    remove_faces(mesh_, cut);
  }

  PolygonMesh& mesh_;
  const Connectivity c_;
  const CapFlipOptions& options_;
  const double cap_cosine_;
  std::vector<uint8_t> touched_; // 1: flipped, 2: cut off, this pass
  std::vector<uint8_t> on_boundary_;
  std::unordered_set<uint64_t> made_; // edges this pass made, which c_ does not know
};

} // namespace

CapFlips flip_caps(PolygonMesh mesh, const CapFlipOptions& options) {
  CapFlips result;
  for (int pass = 0; pass < options.max_passes; ++pass) {
    const CapFlips counts = FlipPass(mesh, options).run();
    result.flips += counts.flips;
    result.cuts += counts.cuts;
    if (counts.flips + counts.cuts == 0) break;
  }
  result.mesh = std::move(mesh);
  return result;
}

} // namespace meander
