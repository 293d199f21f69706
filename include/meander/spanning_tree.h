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

// The ids of the edges of a spanning forest (one tree per connected component),
// increasing. The same graph, strategy and seed give the same forest on every platform.
// Time: O(E α(E)) for random, bfs and dfs; Wilson's algorithm takes the graph's mean
// hitting time (near-linear on meshes).
std::vector<int32_t> spanning_forest(const Graph& graph, TreeStrategy strategy, uint64_t seed);

// The same, taking the graph over (left empty): the random and shaped forests release its
// edges after their first pass, when the graph is the largest thing they hold.
std::vector<int32_t> spanning_forest(Graph&& graph, TreeStrategy strategy, uint64_t seed);

} // namespace meander
