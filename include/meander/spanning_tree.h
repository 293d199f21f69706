// Spanning forests of a graph: the style knob of the curve. The tree decides which quad
// diagonals flip, so its shape is the shape of the meander (ALGORITHM-NOTES: BFS gives
// short bushy branches, DFS long snakes, a uniform random tree the isotropic TSP look).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace meander {

enum class TreeStrategy {
  random,  // Kruskal over a random permutation of the edges (random weights)
  uniform, // Wilson's algorithm: every spanning tree equally likely
  bfs,     // breadth-first from a random root in each component
  dfs,     // depth-first from a random root, neighbours in random order
  shaped,  // Kruskal by Graph::rank, lowest first, in random order within a rank
};

// Parses "random" | "uniform" | "bfs" | "dfs" | "shaped"; throws UsageError otherwise.
TreeStrategy parse_tree_strategy(std::string_view name);
std::string_view to_string(TreeStrategy strategy);

// An undirected multigraph on nodes 0..num_nodes-1; edges may repeat, self loops are
// ignored. `rank` (one per edge, below max_rank, or empty: all alike) orders the edges
// for the shaped strategy; the others ignore it.
struct Graph {
  static constexpr int max_rank = 32;
  int32_t num_nodes = 0;
  std::vector<std::array<int32_t, 2>> edges;
  std::vector<uint8_t> rank;
};

// A multigraph whose edges are read where they lie, in rows of `stride` values, as a quad
// mesh holds them: edge i joins rows[i * stride + first] - bias and rows[i * stride +
// second] - bias, and is absent, like a self loop, when either value is negative. A
// Hamiltonian cycle reads its graph from the quads this way instead of copying the ends
// out: the copy, held in the forest's first round, was the run's peak of memory
// (docs/curve.md, "Large meshes"). `rank` is as Graph::rank.
struct EdgeTable {
  int32_t num_nodes = 0;
  int32_t num_edges = 0;
  const int32_t* rows = nullptr;
  int32_t stride = 2, first = 0, second = 1;
  int32_t bias = 0;
  std::span<const uint8_t> rank;

  // The ends of edge i, {-1, -1} when it is absent.
  std::array<int32_t, 2> ends(int32_t i) const {
    const int32_t* row = rows + size_t(i) * size_t(stride);
    const int32_t u = row[first], v = row[second];
    if (u < 0 || v < 0) return {-1, -1};
    return {u - bias, v - bias};
  }
};

// The ids of the edges of a spanning forest (one tree per connected component),
// increasing. The same graph, strategy and seed give the same forest on every platform.
// Time: O(E α(E)) for random, bfs and dfs; Wilson's algorithm takes the graph's mean
// hitting time (near-linear on meshes).
std::vector<int32_t> spanning_forest(const Graph& graph, TreeStrategy strategy, uint64_t seed);

// The same for a graph read in place. The forest is the one the Graph of the table's
// edges that join two nodes would give, in table ids: the absent edges and self loops
// are passed over as if they were not listed. (A Graph's self loops do take a place.)
std::vector<int32_t> spanning_forest(const EdgeTable& graph, TreeStrategy strategy, uint64_t seed);

// A spanning forest whose waviness `branches` sets, from 0 (long snakes: few leaves) to 1
// (many short branches), continuously: a depth-first walk from a random root in each
// component in which, at each step with probability `branches`, the node it stands on
// first takes all its neighbours still outside the tree as children (those not walked on
// from stay leaves); at 0, TreeStrategy::dfs's forest of the same seed. Leaves grow
// steadily with `branches` (the kitten at 1/60 of its diagonal: 116, 242, 333, 395, 459
// at 0, 0.25, 0.5, 0.75, 1; the random tree gives about 310). Increasing edge ids, the
// same for the same seed. O(E). Throws ParameterError for branches outside [0, 1].
std::vector<int32_t> branching_forest(const EdgeTable& graph, double branches, uint64_t seed);

// The leaves of a forest (ids into `graph`): its nodes of degree 1, the tips of the
// meander's branches. O(nodes + forest).
int64_t count_leaves(const EdgeTable& graph, std::span<const int32_t> forest);

} // namespace meander
