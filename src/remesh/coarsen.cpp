#include "meander/coarsen.h"

#include "meander/connectivity.h"
#include "meander/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

namespace meander {

namespace {

// Thresholds rise over this many passes, so short edges go before longer ones; in each,
// a vertex that took another's place is left alone until the next, so collapses spread
// over the surface. (With 4 passes, or none left alone, a 1M-triangle UV sphere kept 1.6
// to 8 times the faces at lengths of 0.03 to 0.05.)
constexpr uint8_t kPasses = 8;
// A collapse may turn a face's normal by at most 60 degrees, and make no edge longer than
// kLongest times the length.
constexpr double kLeastCosine = 0.5;
constexpr double kLongest = 1.5;
// Nor make a face thinner than this fraction of its longest side (three vertices in a
// line, as on a ruled surface, would make one of no area).
constexpr double kLeastHeight = 1e-3;

class Collapser {
public:
  Collapser(const PolygonMesh& mesh, double length) : length_(length), longest_(kLongest * length) {
    const int32_t faces = mesh.num_faces();
    faces_.reserve(size_t(faces));
    for (int32_t f = 0; f < faces; ++f) {
      if (mesh.face_size(f) != 3)
        throw InputError("face " + std::to_string(f) + " has " + std::to_string(mesh.face_size(f)) +
                         " sides: only triangle meshes are coarsened");
      faces_.push_back({mesh.face(f)[0], mesh.face(f)[1], mesh.face(f)[2]});
    }
    alive_.assign(size_t(faces), 1);
    positions_.reserve(mesh.positions.size());
    for (const Vec3 p : mesh.positions) positions_.push_back(to_double(p));
    mark_.assign(positions_.size(), 0);
    moved_.assign(positions_.size(), 0);
    boundary_.assign(positions_.size(), 0);
    const Connectivity c = build_connectivity(mesh);
    for (int32_t e = 0; e < c.num_edges(); ++e)
      if (c.edge_degree(e) == 1) boundary_[size_t(c.edge_vertices[size_t(e)][0])] = boundary_[size_t(c.edge_vertices[size_t(e)][1])] = 1;
    index_faces();
  }

  void run() {
    for (pass_ = 1; pass_ <= kPasses; ++pass_) {
      const double threshold = length_ * pass_ / kPasses;
      for (size_t f = 0; f < faces_.size(); ++f)
        for (int k = 0; k < 3 && alive_[f]; ++k) {
          const int32_t a = faces_[f][size_t(k)], b = faces_[f][size_t((k + 1) % 3)];
          if (moved_[size_t(a)] == pass_ || moved_[size_t(b)] == pass_) continue;
          if (norm(positions_[size_t(a)] - positions_[size_t(b)]) < threshold && !collapse(b, a)) collapse(a, b);
        }
    }
  }

  PolygonMesh result(const PolygonMesh& mesh) const {
    PolygonMesh out;
    std::vector<int32_t> index(positions_.size(), -1);
    for (size_t f = 0; f < faces_.size(); ++f)
      if (alive_[f])
        for (int32_t v : faces_[f]) index[size_t(v)] = 0;
    for (size_t v = 0; v < index.size(); ++v)
      if (index[v] == 0) {
        index[v] = out.num_vertices();
        out.positions.push_back(mesh.positions[v]);
      }
    for (size_t f = 0; f < faces_.size(); ++f)
      if (alive_[f]) out.add_face({index[size_t(faces_[f][0])], index[size_t(faces_[f][1])], index[size_t(faces_[f][2])]});
    return out;
  }

private:
  // Each vertex's faces: refs_[start_[v] .. + count_[v]), some of them dead. A vertex
  // that takes another's faces gets a new run at the end; when the runs outgrow twice the
  // faces, they are made again.
  void index_faces() {
    start_.assign(positions_.size() + 1, 0);
    count_.assign(positions_.size(), 0);
    for (size_t f = 0; f < faces_.size(); ++f)
      if (alive_[f])
        for (int32_t v : faces_[f]) ++count_[size_t(v)];
    for (size_t v = 0; v < count_.size(); ++v) start_[v + 1] = start_[v] + count_[v];
    refs_.assign(size_t(start_.back()), 0);
    std::vector<int32_t> filled(count_.size(), 0);
    for (size_t f = 0; f < faces_.size(); ++f)
      if (alive_[f])
        for (int32_t v : faces_[f]) refs_[size_t(start_[size_t(v)] + filled[size_t(v)]++)] = int32_t(f);
  }

  std::span<const int32_t> faces_of(int32_t v) const { return {refs_.data() + start_[size_t(v)], size_t(count_[size_t(v)])}; }

  bool has(int32_t f, int32_t v) const {
    const std::array<int32_t, 3>& t = faces_[size_t(f)];
    return t[0] == v || t[1] == v || t[2] == v;
  }

  // The live faces of a that have b.
  int shared_faces(int32_t a, int32_t b) const {
    int n = 0;
    for (int32_t f : faces_of(a)) n += alive_[size_t(f)] && has(f, b);
    return n;
  }

  Vec3d normal(const std::array<int32_t, 3>& t, int32_t moved, Vec3d to) const {
    auto at = [&](int32_t v) { return v == moved ? to : positions_[size_t(v)]; };
    return cross(at(t[1]) - at(t[0]), at(t[2]) - at(t[0]));
  }

  // Collapses v into u if that keeps the topology and the shape; says whether it did.
  bool collapse(int32_t v, int32_t u) {
    if (boundary_[size_t(v)] && !boundary_[size_t(u)]) return false;
    // The faces on edge uv and their third vertices.
    int n = 0;
    std::array<int32_t, 2> opposite{};
    for (int32_t f : faces_of(v)) {
      if (!alive_[size_t(f)] || !has(f, u)) continue;
      if (n == 2) return false;
      for (int32_t w : faces_[size_t(f)])
        if (w != u && w != v) opposite[size_t(n)] = w;
      ++n;
    }
    if (n == 0 || (n == 2 && boundary_[size_t(u)] && boundary_[size_t(v)])) return false;
    // The link condition: u and v have no common neighbour but the opposite vertices.
    tick_ += 2;
    for (int32_t f : faces_of(u))
      if (alive_[size_t(f)])
        for (int32_t w : faces_[size_t(f)]) mark_[size_t(w)] = tick_;
    int common = 0;
    for (int32_t f : faces_of(v))
      if (alive_[size_t(f)])
        for (int32_t w : faces_[size_t(f)])
          if (w != u && w != v && mark_[size_t(w)] == tick_) {
            mark_[size_t(w)] = tick_ + 1;
            ++common;
          }
    if (common != n) return false;
    // Nor do the two faces' third vertices share an edge (a tetrahedron would fold flat),
    // and a boundary loop of three edges stays.
    if (n == 2 && shared_faces(opposite[0], opposite[1]) > 0) return false;
    if (n == 1 && shared_faces(u, opposite[0]) == 1 && shared_faces(v, opposite[0]) == 1) return false;
    const Vec3d to = positions_[size_t(u)];
    for (int32_t f : faces_of(v)) {
      if (!alive_[size_t(f)] || has(f, u)) continue;
      const std::array<int32_t, 3>& t = faces_[size_t(f)];
      const Vec3d before = normal(t, -1, {}), after = normal(t, v, to);
      if (dot(before, after) < kLeastCosine * norm(before) * norm(after)) return false;
      double side = 0; // the face's longest side after
      for (size_t k = 0; k < 3; ++k) {
        const int32_t a = t[k], b = t[(k + 1) % 3];
        side = std::max(side, norm((a == v ? to : positions_[size_t(a)]) - (b == v ? to : positions_[size_t(b)])));
      }
      if (side > longest_ || !(norm(after) >= kLeastHeight * side * side)) return false;
    }
    // Made: the edge's faces go, v's others take u, and u gets both runs.
    run_.clear();
    for (int32_t f : faces_of(u))
      if (alive_[size_t(f)] && !has(f, v)) run_.push_back(f);
    for (int32_t f : faces_of(v)) {
      if (!alive_[size_t(f)]) continue;
      if (has(f, u)) {
        alive_[size_t(f)] = 0;
        continue;
      }
      for (int32_t& w : faces_[size_t(f)])
        if (w == v) w = u;
      run_.push_back(f);
    }
    count_[size_t(v)] = 0;
    moved_[size_t(u)] = pass_;
    if (refs_.size() + run_.size() > 2 * 3 * faces_.size()) {
      index_faces();
      return true;
    }
    start_[size_t(u)] = int32_t(refs_.size());
    count_[size_t(u)] = int32_t(run_.size());
    refs_.insert(refs_.end(), run_.begin(), run_.end());
    return true;
  }

  double length_, longest_;
  std::vector<Vec3d> positions_;
  std::vector<std::array<int32_t, 3>> faces_;
  std::vector<uint8_t> alive_, boundary_;
  std::vector<int32_t> start_, count_, refs_, run_;
  std::vector<uint32_t> mark_;
  uint32_t tick_ = 0;
  std::vector<uint8_t> moved_; // the pass in which a vertex last took another's place
  uint8_t pass_ = 0;
};

} // namespace

PolygonMesh coarsen(const PolygonMesh& mesh, double length) {
  Collapser collapser(mesh, length);
  collapser.run();
  return collapser.result(mesh);
}

} // namespace meander
