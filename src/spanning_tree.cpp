#include "meander/spanning_tree.h"

#include "meander/error.h"
#include "random.h"
#include "union_find.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <numeric>
#include <span>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

// One Borůvka round: adds each node's lightest edge under `weight` (distinct per edge) to
// `forest`, and labels the nodes 0, 1, ... by the trees those edges make, in the order
// of their smallest nodes. Returns the number of labels. Every pass is parallel: with
// distinct weights each tree of lightest edges has exactly one edge chosen from both
// ends, so a node's parent can be the other end of its own lightest edge, the smaller
// node of that doubly chosen edge being the root, and no union-find is needed.
template <typename Weight>
int32_t boruvka_round(const Graph& g, const Weight& weight, std::vector<int32_t>& label, std::vector<int32_t>& forest) {
  const int32_t n = g.num_nodes;
  const auto nodes = tbb::blocked_range<int32_t>(0, n, 1 << 16);
  std::fill(label.begin(), label.end(), -1); // first each node's lightest edge
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, int32_t(g.edges.size()), 1 << 16), [&](const auto& range) {
    for (int32_t e = range.begin(); e < range.end(); ++e) {
      const auto [u, v] = g.edges[size_t(e)];
      if (u == v) continue;
      const uint64_t w = weight(e);
      for (const int32_t x : {u, v}) {
        std::atomic_ref<int32_t> lightest(label[size_t(x)]);
        for (int32_t now = lightest.load(std::memory_order_relaxed); now < 0 || w < weight(now);)
          if (lightest.compare_exchange_weak(now, e, std::memory_order_relaxed)) break;
      }
    }
  });
  const auto other_end = [&](int32_t x) {
    const int32_t e = label[size_t(x)];
    return e < 0 ? x : g.edges[size_t(e)][0] == x ? g.edges[size_t(e)][1] : g.edges[size_t(e)][0];
  };
  std::vector<int32_t> parent(static_cast<size_t>(n));
  tbb::parallel_for(nodes, [&](const auto& range) {
    for (int32_t x = range.begin(); x < range.end(); ++x) {
      const int32_t y = other_end(x);
      parent[size_t(x)] = y != x && other_end(y) == x && x < y ? x : y;
    }
  });
  for (int32_t x = 0; x < n; ++x)
    if (parent[size_t(x)] != x) forest.push_back(label[size_t(x)]);
  // Each node to its root, halving the path as it goes (another thread only ever sees a
  // parent move up towards the same root). Along a path the lightest edges' weights
  // fall, so with random weights paths are short.
  tbb::parallel_for(nodes, [&](const auto& range) {
    const auto up = [&](int32_t x) { return std::atomic_ref<int32_t>(parent[size_t(x)]); };
    for (int32_t x = range.begin(); x < range.end(); ++x) {
      int32_t at = x, p = up(x).load(std::memory_order_relaxed);
      for (int32_t grandparent; (grandparent = up(p).load(std::memory_order_relaxed)) != p;) {
        up(at).store(grandparent, std::memory_order_relaxed);
        at = grandparent;
        p = up(at).load(std::memory_order_relaxed);
      }
      up(x).store(p, std::memory_order_relaxed);
    }
  });
  // The roots numbered in node order: counted by fixed chunks, then numbered in each.
  constexpr int32_t chunks = 64;
  const int32_t chunk = (n + chunks - 1) / chunks;
  std::array<int32_t, chunks + 1> first_tree{};
  tbb::parallel_for(0, chunks, [&](int32_t c) {
    for (int32_t x = c * chunk; x < std::min(n, (c + 1) * chunk); ++x) first_tree[size_t(c) + 1] += parent[size_t(x)] == x;
  });
  for (int32_t c = 0; c < chunks; ++c) first_tree[size_t(c) + 1] += first_tree[size_t(c)];
  tbb::parallel_for(0, chunks, [&](int32_t c) {
    int32_t tree = first_tree[size_t(c)];
    for (int32_t x = c * chunk; x < std::min(n, (c + 1) * chunk); ++x)
      if (parent[size_t(x)] == x) label[size_t(x)] = tree++;
  });
  tbb::parallel_for(nodes, [&](const auto& range) {
    for (int32_t x = range.begin(); x < range.end(); ++x)
      if (parent[size_t(x)] != x) label[size_t(x)] = label[size_t(parent[size_t(x)])];
  });
  return first_tree.back();
}

// Kruskal over the edges in the order of random keys, or with `ranked` by increasing
// Graph::rank and by random key within a rank: the minimum spanning forest of those
// weights (ties by edge id), so every seed's tree is that of a random permutation.
// On a large graph a Borůvka round comes first: each node takes its lightest edge, which
// is always in the minimum forest, in one pass over the edges in their own order
// (neighbouring faces have nearby ids, so this is nearly sequential). That contracts the
// graph to about a third of its nodes, and Kruskal over the edges left then finds in a
// union-find a third the size: on a 10M-face mesh 12 MB, which the cache holds, instead
// of 40 MB, which it does not. Below Graph::contract_from nodes the union-find fits the
// cache anyway and the round costs more than it saves. Either way the forest is the same.
std::vector<int32_t> kruskal_random(const Graph& g, uint64_t seed, bool ranked) {
  const size_t m = g.edges.size();
  ranked = ranked && !g.rank.empty();
  if (ranked && g.rank.size() != m)
    throw UsageError("spanning tree: " + std::to_string(g.rank.size()) + " ranks for " + std::to_string(m) + " edges");
  if (ranked)
    for (size_t e = 0; e < m; ++e)
      if (g.rank[e] >= Graph::max_rank)
        throw UsageError("spanning tree: edge " + std::to_string(e) + " has rank " + std::to_string(g.rank[e]) +
                         " (at most " + std::to_string(Graph::max_rank - 1) + ")");
  // An edge's key: its rank in the top 5 bits when ranked, then random bits from a hash of
  // the edge and the seed. Hashed rather than drawn in turn, so the keys can be made in
  // parallel and stay the same whatever order the passes below take.
  const uint64_t salt = Random(seed).next();
  constexpr int rank_shift = 27;
  static_assert(Graph::max_rank <= (1 << (32 - rank_shift)));
  std::vector<uint32_t> keys(m);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, m, 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t e = r.begin(); e < r.end(); ++e) {
      const uint32_t random = uint32_t(Random(salt ^ (uint64_t(e) * 0xd1b54a32d192ed03ULL)).next() >> 32);
      keys[e] = ranked ? uint32_t(g.rank[e]) << rank_shift | random >> (32 - rank_shift) : random;
    }
  });
  auto key = [&](int32_t e) { return keys[size_t(e)]; };
  auto weight = [&](int32_t e) { return uint64_t(key(e)) << 32 | uint32_t(e); };

  const int32_t n = g.num_nodes;
  std::vector<int32_t> forest;
  forest.reserve(size_t(n));
  std::vector<int32_t> label(static_cast<size_t>(n));
  int32_t contracted = n;
  if (n < Graph::contract_from)
    std::iota(label.begin(), label.end(), 0);
  else
    contracted = boruvka_round(g, weight, label, forest);

  // The edges between contracted nodes in increasing weight: scattered by the top byte of
  // their key into 256 buckets (a few sequential write streams), then each bucket, small
  // enough for the cache, sorted by the other three bytes in stable radix passes. The
  // edges enter in id order, so ties stay in id order, as in `weight`.
  struct Edge {
    int32_t u, v, id;
    uint32_t key;
  };
  constexpr int buckets = 256;
  // In parallel over fixed runs of edge ids, each run writing after the runs before it in
  // every bucket: the same order whatever the number of threads.
  constexpr size_t runs = 16;
  const size_t run_length = (m + runs - 1) / runs;
  std::vector<std::array<size_t, buckets>> at(runs);
  auto for_runs = [&](auto&& body) {
    tbb::parallel_for(size_t(0), runs, [&](size_t r) {
      for (size_t e = r * run_length; e < std::min(m, (r + 1) * run_length); ++e) {
        const int32_t u = label[size_t(g.edges[e][0])], v = label[size_t(g.edges[e][1])];
        if (u != v) body(at[r], int32_t(e), u, v);
      }
    });
  };
  for_runs([&](std::array<size_t, buckets>& count, int32_t e, int32_t, int32_t) { ++count[key(e) >> 24]; });
  std::vector<size_t> start(buckets + 1, 0);
  for (int b = 0; b < buckets; ++b) {
    start[size_t(b) + 1] = start[size_t(b)];
    for (auto& count : at) start[size_t(b) + 1] += std::exchange(count[size_t(b)], start[size_t(b) + 1]);
  }
  std::vector<Edge> order(start.back());
  for_runs([&](std::array<size_t, buckets>& fill, int32_t e, int32_t u, int32_t v) {
    const uint32_t k = key(e);
    order[fill[k >> 24]++] = {u, v, e, k};
  });
  std::vector<int32_t>().swap(label);
  std::vector<uint32_t>().swap(keys);
  tbb::parallel_for(tbb::blocked_range<int>(0, buckets), [&](const tbb::blocked_range<int>& range) {
    std::vector<Edge> spare;
    for (int b = range.begin(); b < range.end(); ++b) {
      const std::span<Edge> edges(order.data() + start[size_t(b)], start[size_t(b) + 1] - start[size_t(b)]);
      spare.resize(edges.size());
      std::span<Edge> from = edges, to(spare);
      for (int shift = 0; shift < 24; shift += 8) {
        std::array<size_t, 257> place{};
        for (const Edge& x : from) ++place[((x.key >> shift) & 0xff) + 1];
        for (int d = 0; d < 256; ++d) place[size_t(d) + 1] += place[size_t(d)];
        for (const Edge& x : from) to[place[(x.key >> shift) & 0xff]++] = x;
        std::swap(from, to);
      }
      // Three passes leave the sorted edges in the spare buffer.
      std::copy(from.begin(), from.end(), edges.begin());
    }
  });

  UnionFind sets(contracted);
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
  case TreeStrategy::random: forest = kruskal_random(graph, seed, false); break;
  case TreeStrategy::shaped: forest = kruskal_random(graph, seed, true); break;
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
