// Taubin's construction (paper Section 3): split every quad along a diagonal, then flip
// the diagonals of the quads on a spanning tree of the loops' adjacency, so that the
// triangles form exactly one closed strip per connected component.
#pragma once

#include "meander/quadrangulate.h"
#include "meander/spanning_tree.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace meander {

struct CycleOptions {
  TreeStrategy tree = TreeStrategy::random;
  uint64_t seed = 1;
  // Set: the tree is branching_forest's with this waviness (0 long snakes .. 1 many short
  // branches) instead of `tree`'s, which must then be random, the default (the others
  // are trees of their own: ParameterError).
  std::optional<double> branches;
  // Count the tree's leaves into TriangleCycle::leaves (a pass over the tree).
  bool count_leaves = false;
  // The diagonals to start from, one per quad as TriangleCycle::diagonal (half quads 0);
  // empty: every quad starts split along corners 0-2. The duotone's flip rule starts
  // from random ones, as the paper's Section 5.3 does.
  std::span<const uint8_t> initial_diagonal;
  friend bool operator==(const CycleOptions& a, const CycleOptions& b) { // the diagonals by content
    return a.tree == b.tree && a.seed == b.seed && a.branches == b.branches && a.count_leaves == b.count_leaves &&
           std::ranges::equal(a.initial_diagonal, b.initial_diagonal);
  }
};

// The Hamiltonian cycles of the triangulated quad mesh. Cycle k is the triangles
// order[cycle_start[k] .. cycle_start[k+1]) in order; consecutive triangles (and the last
// and the first) share a quad side. A triangle is named 4*q + apex: quad q and the corner
// between its two quad sides (the paper's p00 = p01); cycle_triangle() gives its vertices.
// One int per triangle rather than three keeps the largest array of the pipeline small.
// diagonal[q] is 0 when quad q is split along corners 0-2 and 1 along corners 1-3.
struct TriangleCycle {
  std::vector<int32_t> order;
  std::vector<int32_t> cycle_start{0};
  std::vector<uint8_t> diagonal;
  // With CycleOptions::count_leaves: the spanning tree's leaves, each the tip of a branch
  // of the meander; -1 otherwise.
  int64_t leaves = -1;

  int32_t num_cycles() const { return int32_t(cycle_start.size()) - 1; }
  int32_t num_triangles() const { return int32_t(order.size()); }
};

// The vertices (p, apex, n) of triangle `id` (= 4*q + apex): the apex between p and n,
// which are the ends of the diagonal, in the quad's orientation.
inline std::array<int32_t, 3> cycle_triangle(const QuadMesh& quads, int32_t id) {
  const auto& c = quads.quads[size_t(id >> 2)];
  const int a = id & 3;
  return {c[size_t((a + 3) & 3)], c[size_t(a)], c[size_t((a + 1) & 3)]};
}

// Told, on the thread that walks the final cycles, what of them is settled while the walk
// goes on, so that another thread can use it before hamiltonian_cycle returns: a writer
// samples and writes the curve of the triangles walked so far while the rest is walked.
// `walked` is a prefix of the result's order, in memory that stays where it is and
// unchanged while the result lives; `cycle_start` is the result's cycle_start so far
// (valid during the call only), its last entry the start of the cycle still being walked,
// or walked.size() when none is. Called every `every` triangles and when the walk ends.
struct WalkObserver {
  int64_t every = int64_t(1) << 20;
  std::function<void(std::span<const int32_t> walked, std::span<const int32_t> cycle_start)> seen;
};

// Builds one cycle per connected component of the quad mesh (components joined across
// quad sides). Every full quad contributes two triangles, a half quad one. Time O(quads)
// plus the spanning forest. Throws TopologyError if a full quad has a side with no
// neighbour (a quad mesh with boundary: only half quads may end at a boundary), and
// UsageError above 2^29 quads (triangle names must fit an int32).
TriangleCycle hamiltonian_cycle(const QuadMesh& quads, const CycleOptions& options = {},
                                const WalkObserver* observer = nullptr);

// The loops of the triangulation that `diagonal` gives, without any flip: as many as
// they are (the duotone's tree rule chooses diagonals that leave one per component).
// Same requirements and layout as hamiltonian_cycle; O(quads).
TriangleCycle triangle_loops(const QuadMesh& quads, std::vector<uint8_t> diagonal);

// Independent check of a cycle against its quad mesh, sharing no code with the
// construction: every triangle of the triangulation given by `diagonal` appears exactly
// once, consecutive triangles share two vertices, and there is exactly one cycle per
// connected component. Returns "" when it holds, else the first violation found.
// O(quads + triangles), plus a log factor in the number of cycles.
std::string verify_cycle(const QuadMesh& quads, const TriangleCycle& cycle);

// The certificate of the cycle: the triangulated quad mesh with its triangles in cycle
// order, one group per cycle (write it with MeshWriteOptions::group_start = cycle_start).
PolygonMesh cycle_triangles(const QuadMesh& quads, const TriangleCycle& cycle);

} // namespace meander
