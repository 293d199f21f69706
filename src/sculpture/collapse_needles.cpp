#include "meander/collapse_needles.h"

#include "meander/connectivity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace meander {

namespace {

class CollapsePass {
public:
  CollapsePass(PolygonMesh& mesh, const NeedleCollapseOptions& options)
      : mesh_(mesh), options_(options), needle_cosine_(std::cos(options.needle_angle_degrees * std::numbers::pi / 180)),
        touched_(size_t(mesh.num_faces()), 0), on_boundary_(size_t(mesh.num_vertices()), 0) {
    const Connectivity c = build_connectivity(mesh);
    for (int32_t e = 0; e < c.num_edges(); ++e)
      if (c.edge_degree(e) == 1) {
        const auto [lo, hi] = c.edge_vertices[size_t(e)];
        on_boundary_[size_t(lo)] = on_boundary_[size_t(hi)] = 1;
        boundary_edges_.push_back(c.edge_vertices[size_t(e)]);
      }
    // The faces around each vertex, as a counting sort of the corners.
    vertex_face_start_.assign(size_t(mesh.num_vertices()) + 1, 0);
    for (const int32_t v : mesh.face_vertices) ++vertex_face_start_[size_t(v) + 1];
    for (size_t v = 0; v + 1 < vertex_face_start_.size(); ++v) vertex_face_start_[v + 1] += vertex_face_start_[v];
    vertex_faces_.resize(mesh.face_vertices.size());
    std::vector<int32_t> fill(vertex_face_start_.begin(), vertex_face_start_.end() - 1);
    for (int32_t f = 0; f < mesh.num_faces(); ++f)
      for (const int32_t v : mesh.face(f)) vertex_faces_[size_t(fill[size_t(v)]++)] = f;
  }

  // One pass over the faces in order; a collapse touches every face around its edge's
  // ends, and a face is changed at most once, so each collapse reads the mesh as the
  // face lists saw it.
  int64_t run() {
    int64_t collapses = 0;
    std::vector<uint8_t> removed(size_t(mesh_.num_faces()), 0);
    for (int32_t f = 0; f < mesh_.num_faces(); ++f) {
      if (mesh_.face_size(f) != 3 || touched_[size_t(f)]) continue;
      const auto t = mesh_.face(f);
      // The smallest angle faces the shortest side.
      int k = 0;
      double shortest = INFINITY, longest = 0;
      for (int i = 0; i < 3; ++i) {
        const double side = norm(at(t[size_t((i + 1) % 3)]) - at(t[size_t((i + 2) % 3)]));
        if (side < shortest) shortest = side, k = i;
        longest = std::max(longest, side);
      }
      const int32_t o = t[size_t(k)], u = t[size_t((k + 1) % 3)], v = t[size_t((k + 2) % 3)];
      const Vec3 ou = at(u) - at(o), ov = at(v) - at(o);
      const bool needle = shortest <= options_.max_move * longest && dot(ou, ov) > needle_cosine_ * norm(ou) * norm(ov);
      if ((needle || folded(f)) && collapse(u, v, removed)) ++collapses;
    }
    if (collapses > 0) remove_faces(mesh_, removed);
    return collapses;
  }

private:
  Vec3 at(int32_t v) const { return mesh_.positions[size_t(v)]; }
  std::span<const int32_t> faces_of(int32_t v) const {
    return {vertex_faces_.data() + vertex_face_start_[size_t(v)], size_t(vertex_face_start_[size_t(v) + 1] - vertex_face_start_[size_t(v)])};
  }
  bool is_boundary_edge(int32_t u, int32_t v) const {
    return std::binary_search(boundary_edges_.begin(), boundary_edges_.end(), std::array{std::min(u, v), std::max(u, v)});
  }

  Vec3 area(int32_t f) const {
    const auto t = mesh_.face(f);
    return cross(at(t[1]) - at(t[0]), at(t[2]) - at(t[0]));
  }

  // Triangle f faces against each of its neighbours: a scan's fold, a sliver turned
  // over, whose dual-of-Simplest triangles turn the cycle back over itself whatever its
  // shape (on camelhead, a cap of 174 degrees whose flip would fold too). A neighbour
  // wound the other way (on a non-orientable surface) is compared turned round, so that
  // only the geometry counts.
  bool folded(int32_t f) const {
    const auto t = mesh_.face(f);
    const Vec3 own = area(f);
    int neighbours = 0;
    for (size_t i = 0; i < 3; ++i) {
      const int32_t a = t[i], b = t[(i + 1) % 3];
      for (const int32_t g : faces_of(a)) {
        const auto corners = mesh_.face(g);
        const auto at_a = std::find(corners.begin(), corners.end(), a);
        const int32_t after_a = at_a + 1 == corners.end() ? corners.front() : *(at_a + 1);
        if (g == f || std::find(corners.begin(), corners.end(), b) == corners.end()) continue;
        if (!(dot(area(g), own) * (after_a == b ? -1 : 1) < 0)) return false;
        ++neighbours;
      }
    }
    return neighbours > 0;
  }

  bool collapse(int32_t u, int32_t v, std::vector<uint8_t>& removed) {
    if (on_boundary_[size_t(u)] && on_boundary_[size_t(v)] && !is_boundary_edge(u, v)) return false; // it would pinch the surface
    const Vec3 target = on_boundary_[size_t(u)] == on_boundary_[size_t(v)] ? (at(u) + at(v)) * 0.5f : on_boundary_[size_t(u)] ? at(u) : at(v);
    // The faces on the edge go; every other face around u or v keeps its place, with
    // the merged vertex in u's or v's corner.
    shared_.clear(), kept_.clear();
    for (const int32_t w : {u, v})
      for (const int32_t g : faces_of(w)) {
        if (mesh_.face_size(g) != 3 || touched_[size_t(g)]) return false;
        const auto corners = mesh_.face(g);
        const bool both = std::find(corners.begin(), corners.end(), w == u ? v : u) != corners.end();
        if (both) {
          if (w == u) shared_.push_back(g);
        } else {
          kept_.push_back(g);
        }
      }
    if (shared_.empty() || shared_.size() > 2 || kept_.empty()) return false;
    Vec3 facing{0, 0, 0}; // the way the surface around the edge faces
    for (const int32_t g : kept_) facing = facing + area(g);
    for (const int32_t g : shared_) facing = facing + area(g);
    // Manifold afterwards: the only neighbours u and v share are the third corners of
    // the faces on the edge (the link condition).
    opposite_.clear(), neighbours_.clear();
    for (const int32_t g : shared_)
      for (const int32_t x : mesh_.face(g))
        if (x != u && x != v) opposite_.push_back(x);
    for (const int32_t g : kept_) {
      const auto corners = mesh_.face(g);
      const bool of_u = std::find(corners.begin(), corners.end(), u) != corners.end();
      for (const int32_t x : corners)
        if (x != u && x != v) neighbours_.push_back({x, of_u});
    }
    std::sort(neighbours_.begin(), neighbours_.end());
    neighbours_.erase(std::unique(neighbours_.begin(), neighbours_.end()), neighbours_.end());
    for (size_t i = 0; i + 1 < neighbours_.size(); ++i) // (x, v's) then (x, u's): a neighbour of both
      if (neighbours_[i].first == neighbours_[i + 1].first &&
          std::find(opposite_.begin(), opposite_.end(), neighbours_[i].first) == opposite_.end())
        return false;
    // Every face that stays faces the way the surface around does (where it folds,
    // how far a face turns says nothing), none turns over or far (its new normal within
    // 60 degrees of the old), and no two faces around the merged vertex have the same
    // other corners.
    pairs_.clear();
    for (const int32_t g : kept_) {
      const auto corners = mesh_.face(g);
      std::array<Vec3, 3> before{}, after{};
      std::array<int32_t, 2> others{};
      int n = 0;
      for (size_t i = 0; i < 3; ++i) {
        before[i] = after[i] = at(corners[i]);
        if (corners[i] == u || corners[i] == v) after[i] = target;
        else others[size_t(n++)] = corners[i];
      }
      const Vec3 was = cross(before[1] - before[0], before[2] - before[0]), is = cross(after[1] - after[0], after[2] - after[0]);
      if (!(dot(was, facing) > 0) || !(dot(was, is) > 0.5 * norm(was) * norm(is))) return false;
      pairs_.push_back({std::min(others[0], others[1]), std::max(others[0], others[1])});
    }
    std::sort(pairs_.begin(), pairs_.end());
    if (std::adjacent_find(pairs_.begin(), pairs_.end()) != pairs_.end()) return false;

    mesh_.positions[size_t(u)] = target;
    for (const int32_t g : kept_) {
      int32_t* corners = mesh_.face_vertices.data() + mesh_.face_start[size_t(g)];
      std::replace(corners, corners + 3, v, u);
      touched_[size_t(g)] = 1;
    }
    for (const int32_t g : shared_) touched_[size_t(g)] = 1, removed[size_t(g)] = 1;
    return true;
  }

  PolygonMesh& mesh_;
  const NeedleCollapseOptions& options_;
  const double needle_cosine_;
  std::vector<uint8_t> touched_;
  std::vector<uint8_t> on_boundary_;
  std::vector<std::array<int32_t, 2>> boundary_edges_; // sorted, as the connectivity numbers edges
  std::vector<int32_t> vertex_face_start_, vertex_faces_;
  // Scratch for one collapse.
  std::vector<int32_t> shared_, kept_, opposite_;
  std::vector<std::pair<int32_t, bool>> neighbours_;
  std::vector<std::array<int32_t, 2>> pairs_;
};

} // namespace

NeedleCollapses collapse_needles(PolygonMesh mesh, const NeedleCollapseOptions& options) {
  NeedleCollapses result;
  for (int pass = 0; pass < options.max_passes; ++pass) {
    const int64_t collapses = CollapsePass(mesh, options).run();
    result.collapses += collapses;
    if (collapses == 0) break;
  }
  if (result.collapses > 0) { // the merged edges' second ends are left unused
    std::vector<uint8_t> used(mesh.positions.size(), 0);
    for (const int32_t v : mesh.face_vertices) used[size_t(v)] = 1;
    keep_vertices(mesh, used);
  }
  result.mesh = std::move(mesh);
  return result;
}

} // namespace meander
