#include "meander/spanning_tree.h"

#include "meander/error.h"
#include "random.h"
#include "union_find.h"

#include <algorithm>
#include <string>

namespace meander {

TreeStrategy parse_tree_strategy(std::string_view name) {
  if (name == "random") return TreeStrategy::random;
  if (name == "shaped") return TreeStrategy::shaped;
  if (name == "uniform") return TreeStrategy::uniform;
  if (name == "bfs") return TreeStrategy::bfs;
  if (name == "dfs") return TreeStrategy::dfs;
  throw UsageError("unknown tree strategy '" + std::string(name) + "' (expected random, uniform, bfs, dfs or shaped)");
}

std::string_view to_string(TreeStrategy strategy) {
  switch (strategy) {
  case TreeStrategy::random: return "random";
  case TreeStrategy::uniform: return "uniform";
  case TreeStrategy::bfs: return "bfs";
  case TreeStrategy::dfs: return "dfs";
  case TreeStrategy::shaped: return "shaped";
  }
  return "?";
}

namespace {

// Adjacency in CSR form: node u's incident (neighbour, edge id) pairs are
// adjacency[start[u] .. start[u+1]).
struct Adjacency {
  std::vector<int32_t> start;
  std::vector<std::array<int32_t, 2>> adjacent;
  int32_t degree(int32_t u) const { return start[size_t(u) + 1] - start[size_t(u)]; }
};

Adjacency build_adjacency(const Graph& g) {
  Adjacency a;
  a.start.assign(size_t(g.num_nodes) + 1, 0);
  for (const auto& [u, v] : g.edges)
    if (u != v) {
      ++a.start[size_t(u) + 1];
      ++a.start[size_t(v) + 1];
    }
  for (int32_t n = 0; n < g.num_nodes; ++n) a.start[size_t(n) + 1] += a.start[size_t(n)];
  a.adjacent.resize(size_t(a.start.back()));
  std::vector<int32_t> fill(a.start.begin(), a.start.end() - 1);
  for (int32_t e = 0; e < int32_t(g.edges.size()); ++e) {
    const auto [u, v] = g.edges[size_t(e)];
    if (u == v) continue;
    a.adjacent[size_t(fill[size_t(u)]++)] = {v, e};
    a.adjacent[size_t(fill[size_t(v)]++)] = {u, e};
  }
  return a;
}

// Kruskal over the edges in random order, or with `ranked` by increasing Graph::rank and
// in random order within a rank.
std::vector<int32_t> kruskal_random(const Graph& g, Random& rng, bool ranked) {
  // Shuffling the edges themselves (not their ids) lets the loop below read them in
  // order and ask for the union-find entries of edges a few steps ahead, so the cache
  // misses of the random order overlap instead of queueing.
  struct Edge {
    int32_t u, v, id;
  };
  // A uniform shuffle in two cache-friendly steps: scatter every edge into one of a few
  // hundred buckets chosen at random (a few sequential write streams), then shuffle each
  // bucket, small enough to stay in cache. Random bucket sizes and uniform shuffles
  // inside them make every order equally likely, like one Fisher-Yates pass, without its
  // cache miss per swap. Ranked, each rank has its own run of buckets.
  constexpr uint32_t buckets = 256;
  const size_t m = g.edges.size();
  ranked = ranked && !g.rank.empty();
  if (ranked && g.rank.size() != m)
    throw UsageError("spanning tree: " + std::to_string(g.rank.size()) + " ranks for " + std::to_string(m) + " edges");
  constexpr uint32_t per_rank = buckets / Graph::max_rank;
  std::vector<uint8_t> bucket_of(m);
  std::vector<size_t> start(buckets + 1, 0);
  for (size_t i = 0; i < m; ++i) {
    if (ranked && g.rank[i] >= Graph::max_rank)
      throw UsageError("spanning tree: edge " + std::to_string(i) + " has rank " + std::to_string(g.rank[i]) + " (at most " +
                       std::to_string(Graph::max_rank - 1) + ")");
    bucket_of[i] = uint8_t(ranked ? g.rank[i] * per_rank + rng.below(per_rank) : rng.below(buckets));
    ++start[bucket_of[i] + 1];
  }
  for (uint32_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<Edge> order(m);
  {
    std::vector<size_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < m; ++i) order[fill[bucket_of[i]]++] = {g.edges[i][0], g.edges[i][1], int32_t(i)};
  }
  std::vector<uint8_t>().swap(bucket_of);
  for (uint32_t b = 0; b < buckets; ++b)
    for (size_t n = start[b + 1] - start[b]; n > 1; --n) std::swap(order[start[b] + n - 1], order[start[b] + rng.below(uint32_t(n))]);
  UnionFind sets(g.num_nodes);
  std::vector<int32_t> forest;
  forest.reserve(size_t(g.num_nodes));
  constexpr size_t ahead = 8;
  for (size_t i = 0; i < order.size(); ++i) {
    if (i + ahead < order.size()) {
      sets.prefetch(order[i + ahead].u);
      sets.prefetch(order[i + ahead].v);
    }
    if (sets.unite(order[i].u, order[i].v)) forest.push_back(order[i].id);
  }
  return forest;
}

// Nodes in a rotated order starting at a random node: the first node of each component
// in this order is its root, so the seed moves the roots without a pass to find the
// components first.
struct RotatedNodes {
  int32_t n, offset;
  RotatedNodes(int32_t count, Random& rng) : n(count), offset(count > 0 ? int32_t(rng.below(uint32_t(count))) : 0) {}
  int32_t operator[](int32_t i) const { return i + offset < n ? i + offset : i + offset - n; }
};

std::vector<int32_t> breadth_first(const Graph& g, Random& rng) {
  const Adjacency a = build_adjacency(g);
  const RotatedNodes nodes(g.num_nodes, rng);
  std::vector<uint8_t> seen(size_t(g.num_nodes), 0);
  std::vector<int32_t> forest, queue;
  forest.reserve(size_t(g.num_nodes));
  queue.reserve(size_t(g.num_nodes));
  for (int32_t i = 0; i < g.num_nodes; ++i) {
    const int32_t root = nodes[i];
    if (seen[size_t(root)]) continue;
    seen[size_t(root)] = 1;
    queue.push_back(root);
    for (size_t q = queue.size() - 1; q < queue.size(); ++q)
      for (int32_t k = a.start[size_t(queue[q])]; k < a.start[size_t(queue[q]) + 1]; ++k) {
        const auto [n, e] = a.adjacent[size_t(k)];
        if (!seen[size_t(n)]) {
          seen[size_t(n)] = 1;
          forest.push_back(e);
          queue.push_back(n);
        }
      }
  }
  return forest;
}

std::vector<int32_t> depth_first(const Graph& g, Random& rng) {
  const Adjacency a = build_adjacency(g);
  const RotatedNodes nodes(g.num_nodes, rng);
  std::vector<uint8_t> seen(size_t(g.num_nodes), 0);
  // Each node scans its neighbours once, starting at a random offset, so the walk turns
  // differently for each seed while the total work stays linear.
  std::vector<int32_t> offset(size_t(g.num_nodes)), scanned(size_t(g.num_nodes), 0);
  std::vector<int32_t> forest, stack;
  forest.reserve(size_t(g.num_nodes));
  auto enter = [&](int32_t n) {
    seen[size_t(n)] = 1;
    offset[size_t(n)] = int32_t(rng.below(uint32_t(std::max(1, a.degree(n)))));
    stack.push_back(n);
  };
  for (int32_t i = 0; i < g.num_nodes; ++i) {
    if (seen[size_t(nodes[i])]) continue;
    enter(nodes[i]);
    while (!stack.empty()) {
      const int32_t u = stack.back();
      if (scanned[size_t(u)] == a.degree(u)) {
        stack.pop_back();
        continue;
      }
      const int32_t k = a.start[size_t(u)] + (offset[size_t(u)] + scanned[size_t(u)]++) % a.degree(u);
      const auto [n, e] = a.adjacent[size_t(k)];
      if (seen[size_t(n)]) continue;
      forest.push_back(e);
      enter(n);
    }
  }
  return forest;
}

// Wilson's algorithm: loop-erased random walks from each node until they hit the tree.
// The walk remembers only the last edge it left each node by, which erases loops.
std::vector<int32_t> wilson(const Graph& g, Random& rng) {
  const Adjacency a = build_adjacency(g);
  // Each component needs a root before walks start, or a walk in it would never end;
  // which node does not change the distribution of the tree. Components by union-find
  // in edge order, which is cache-friendly.
  const RotatedNodes nodes(g.num_nodes, rng);
  std::vector<uint8_t> in_tree(size_t(g.num_nodes), 0);
  {
    UnionFind components(g.num_nodes);
    for (const auto& [u, v] : g.edges) components.unite(u, v);
    std::vector<uint8_t> rooted(size_t(g.num_nodes), 0);
    for (int32_t i = 0; i < g.num_nodes; ++i) {
      const int32_t c = components.find(nodes[i]);
      if (!rooted[size_t(c)]) rooted[size_t(c)] = in_tree[size_t(nodes[i])] = 1;
    }
  }
  std::vector<int32_t> next_node(size_t(g.num_nodes), -1), next_edge(size_t(g.num_nodes), -1);
  std::vector<int32_t> forest;
  forest.reserve(size_t(g.num_nodes));
  for (int32_t s = 0; s < g.num_nodes; ++s) {
    for (int32_t u = s; !in_tree[size_t(u)];) {
      const auto [n, e] = a.adjacent[size_t(a.start[size_t(u)] + int32_t(rng.below(uint32_t(a.degree(u)))))];
      next_node[size_t(u)] = n;
      next_edge[size_t(u)] = e;
      u = n;
    }
    for (int32_t u = s; !in_tree[size_t(u)]; u = next_node[size_t(u)]) {
      in_tree[size_t(u)] = 1;
      forest.push_back(next_edge[size_t(u)]);
    }
  }
  return forest;
}

} // namespace

std::vector<int32_t> spanning_forest(const Graph& graph, TreeStrategy strategy, uint64_t seed) {
  Random rng(seed);
  std::vector<int32_t> forest;
  switch (strategy) {
  case TreeStrategy::random: forest = kruskal_random(graph, rng, false); break;
  case TreeStrategy::shaped: forest = kruskal_random(graph, rng, true); break;
  case TreeStrategy::uniform: forest = wilson(graph, rng); break;
  case TreeStrategy::bfs: forest = breadth_first(graph, rng); break;
  case TreeStrategy::dfs: forest = depth_first(graph, rng); break;
  }
  // Increasing order through a mark per edge: linear, unlike sorting.
  std::vector<uint8_t> in_forest(graph.edges.size(), 0);
  for (int32_t e : forest) in_forest[size_t(e)] = 1;
  forest.clear();
  for (size_t e = 0; e < in_forest.size(); ++e)
    if (in_forest[e]) forest.push_back(int32_t(e));
  return forest;
}

} // namespace meander
