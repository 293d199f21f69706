#include "meander/spanning_tree.h"

#include "meander/error.h"
#include "chunks.h"
#include "random.h"
#include "union_find.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <numeric>
#include <optional>
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

Adjacency build_adjacency(const EdgeTable& g) {
  Adjacency a;
  a.start.assign(size_t(g.num_nodes) + 1, 0);
  for (int32_t e = 0; e < g.num_edges; ++e)
    if (const auto [u, v] = g.ends(e); u != v) {
      ++a.start[size_t(u) + 1];
      ++a.start[size_t(v) + 1];
    }
  for (int32_t n = 0; n < g.num_nodes; ++n) a.start[size_t(n) + 1] += a.start[size_t(n)];
  a.adjacent.resize(size_t(a.start.back()));
  std::vector<int32_t> fill(a.start.begin(), a.start.end() - 1);
  for (int32_t e = 0; e < g.num_edges; ++e) {
    const auto [u, v] = g.ends(e);
    if (u == v) continue;
    a.adjacent[size_t(fill[size_t(u)]++)] = {v, e};
    a.adjacent[size_t(fill[size_t(v)]++)] = {u, e};
  }
  return a;
}

// An edge as a Borůvka round weighs it: its key (random bits, under the rank when
// ranked) in the high half and its place in the list of edges left in the low half, which
// orders edges as their ids do, since every list keeps the order of the one before.
using Weight = uint64_t;
inline Weight weigh(uint32_t key, int32_t place) { return Weight(key) << 32 | uint32_t(place); }
inline int32_t place_of(Weight w) { return int32_t(uint32_t(w)); }

// An edge between two trees of the forest so far: the trees' labels and the edge's id in
// the graph.
struct TreeEdge {
  int32_t u, v, id;
};

// The graph's edges as the first round reads them. Keys are hashed where they are
// needed, once per edge and round, which costs less than keeping them.
template <typename Key>
struct GraphEdges {
  const EdgeTable& g;
  const Key& key;
  int32_t size() const { return g.num_edges; }
  std::array<int32_t, 2> ends(int32_t i) const { return g.ends(i); }
  int32_t id(int32_t i) const { return i; }
  Weight weight(int32_t i) const { return weigh(key(i), i); }
};

template <typename Key>
struct TreeEdges {
  const std::vector<TreeEdge>& edges;
  const Key& key;
  int32_t size() const { return int32_t(edges.size()); }
  std::array<int32_t, 2> ends(int32_t i) const { return {edges[size_t(i)].u, edges[size_t(i)].v}; }
  int32_t id(int32_t i) const { return edges[size_t(i)].id; }
  Weight weight(int32_t i) const { return weigh(key(id(i)), i); }
};

// Each of the n nodes' lightest edge, as its weight, which holds the edge's place: a
// minimum found without fetching the weight of the edge to beat. Each chunk of edges
// lowers the nodes of the same share of the node range with plain loads and stores, and
// sets its other lowerings aside for a second pass, which makes them with atomic
// compare-and-swaps: edges come about in their nodes' order (a mesh's locality order,
// which the rounds' labels keep), so few are set aside (2 % in the first round on the
// 10M sphere), while a locked compare-and-swap for every lowering made this pass 40 %
// slower (the lock waits for the cache miss before it, and the misses after it wait
// for the lock). Past an eighth of a chunk's edges, the rest of its foreign ends are
// found again in the second pass instead of being kept.
template <typename Edges>
std::vector<Weight> lightest_edges(int32_t n, const Edges& edges) {
  std::vector<Weight> lightest(size_t(n), ~Weight(0));
  struct Aside {
    std::vector<std::pair<int32_t, Weight>> lowerings;
    int32_t unkept_from = -1; // the first edge whose foreign ends are not kept
  };
  std::array<Aside, kChunks> aside;
  const auto share = [&](int32_t c) { return int32_t(int64_t(n) * c / kChunks); };
  for_chunks(edges.size(), [&](int32_t c, int32_t begin, int32_t end) {
    const int32_t first = share(c), last = share(c + 1);
    Aside& a = aside[size_t(c)];
    const size_t most = size_t(end - begin) / 8 + 64;
    for (int32_t i = begin; i < end; ++i) {
      const auto [u, v] = edges.ends(i);
      if (u == v) continue;
      const Weight w = edges.weight(i);
      for (const int32_t x : {u, v})
        if (x >= first && x < last)
          lightest[size_t(x)] = std::min(lightest[size_t(x)], w);
        else if (a.unkept_from < 0 && a.lowerings.size() < most)
          a.lowerings.emplace_back(x, w);
        else if (a.unkept_from < 0)
          a.unkept_from = i;
    }
  });
  for_chunks(edges.size(), [&](int32_t c, int32_t, int32_t end) {
    const auto lower = [&](int32_t x, Weight w) {
      std::atomic_ref<Weight> least(lightest[size_t(x)]);
      for (Weight now = least.load(std::memory_order_relaxed); w < now;)
        if (least.compare_exchange_weak(now, w, std::memory_order_relaxed)) break;
    };
    const Aside& a = aside[size_t(c)];
    for (const auto& [x, w] : a.lowerings) lower(x, w);
    if (a.unkept_from < 0) return;
    const int32_t first = share(c), last = share(c + 1);
    for (int32_t i = a.unkept_from; i < end; ++i) {
      const auto [u, v] = edges.ends(i);
      if (u == v) continue;
      for (const int32_t x : {u, v})
        if (x < first || x >= last) lower(x, edges.weight(i));
    }
  });
  return lightest;
}

// One Borůvka round over n nodes: marks each node's lightest edge in `in_forest`, and labels
// the nodes 0, 1, ... by the trees those edges make, in the order of their smallest
// nodes. Returns the number of labels. Every pass is parallel: with distinct weights each
// tree of lightest edges has exactly one edge chosen from both ends, so a node's parent
// can be the other end of its own lightest edge, the smaller node of that doubly chosen
// edge being the root, and no union-find is needed.
template <typename Edges>
int32_t boruvka_round(int32_t n, const Edges& edges, std::vector<int32_t>& label, std::vector<uint8_t>& in_forest) {
  const auto nodes = tbb::blocked_range<int32_t>(0, n, 1 << 16);
  std::vector<Weight> lightest = lightest_edges(n, edges);
  const auto other_end = [&](int32_t x) {
    if (lightest[size_t(x)] == ~Weight(0)) return x;
    const auto [u, v] = edges.ends(place_of(lightest[size_t(x)]));
    return u == x ? v : u;
  };
  // In one pass: each node's parent; the edge of each node that is not a root marked (an
  // edge added is the lightest of exactly one such node, so it is marked once); the roots
  // counted by chunk, to be numbered in node order (the halving below keeps them).
  std::vector<int32_t> parent(static_cast<size_t>(n));
  std::array<int32_t, kChunks + 1> first_tree{};
  for_chunks(n, [&](int32_t c, int32_t begin, int32_t end) {
    int32_t roots = 0;
    for (int32_t x = begin; x < end; ++x) {
      const int32_t y = other_end(x);
      if (y == x || (x < y && other_end(y) == x)) {
        parent[size_t(x)] = x;
        ++roots;
      } else {
        parent[size_t(x)] = y;
        in_forest[size_t(edges.id(place_of(lightest[size_t(x)])))] = 1;
      }
    }
    first_tree[size_t(c) + 1] = roots;
  });
  std::partial_sum(first_tree.begin(), first_tree.end(), first_tree.begin());
  std::vector<Weight>().swap(lightest);
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
  // The roots numbered in node order, then every node labelled by its root.
  label.resize(size_t(n));
  for_chunks(n, [&](int32_t c, int32_t begin, int32_t end) {
    int32_t tree = first_tree[size_t(c)];
    for (int32_t x = begin; x < end; ++x)
      if (parent[size_t(x)] == x) label[size_t(x)] = tree++;
  });
  // A halving step of another thread may have moved a node's parent back below its root
  // after the node's own last step (a late store of an ancestor read before): parents
  // only ever point higher on the same path, so the root is found by following them.
  tbb::parallel_for(nodes, [&](const auto& range) {
    for (int32_t x = range.begin(); x < range.end(); ++x) {
      int32_t root = parent[size_t(x)];
      while (parent[size_t(root)] != root) root = parent[size_t(root)];
      if (root != x) label[size_t(x)] = label[size_t(root)];
    }
  });
  return first_tree.back();
}

// The edges that join two different trees of `label`, between those trees, in their
// order.
template <typename Edges>
std::vector<TreeEdge> edges_between_trees(const Edges& edges, const std::vector<int32_t>& label) {
  const auto joins = [&](int32_t i) {
    const auto [u, v] = edges.ends(i);
    return u != v && label[size_t(u)] != label[size_t(v)];
  };
  const auto at = chunk_offsets(edges.size(), [&](int32_t begin, int32_t end) {
    int32_t count = 0;
    for (int32_t i = begin; i < end; ++i) count += joins(i);
    return count;
  });
  std::vector<TreeEdge> between(size_t(at.back()));
  for_chunks(edges.size(), [&](int32_t c, int32_t begin, int32_t end) {
    for (int32_t i = begin, next = at[size_t(c)]; i < end; ++i)
      if (joins(i)) {
        const auto [u, v] = edges.ends(i);
        between[size_t(next++)] = {label[size_t(u)], label[size_t(v)], edges.id(i)};
      }
  });
  return between;
}

// Keeps, in place and in their order, the edges that join two different trees of
// `label`, now between those trees: a round's edges are the largest array it makes, and
// two lists at once were the run's peak. Each chunk packs its edges at its own start,
// then the chunks close up in order.
void keep_edges_between_trees(std::vector<TreeEdge>& edges, const std::vector<int32_t>& label) {
  std::array<int32_t, kChunks + 1> kept{};
  for_chunks(int32_t(edges.size()), [&](int32_t c, int32_t begin, int32_t end) {
    int32_t next = begin;
    for (int32_t i = begin; i < end; ++i) {
      const TreeEdge e = edges[size_t(i)];
      const int32_t u = label[size_t(e.u)], v = label[size_t(e.v)];
      if (u != v) edges[size_t(next++)] = {u, v, e.id};
    }
    kept[size_t(c) + 1] = next - begin;
  });
  size_t size = 0;
  for (int32_t c = 0; c < kChunks; ++c) {
    const auto from = edges.begin() + chunk_begin(int32_t(edges.size()), c);
    std::move(from, from + kept[size_t(c) + 1], edges.begin() + ptrdiff_t(size));
    size += size_t(kept[size_t(c) + 1]);
  }
  edges.resize(size);
}

// The minimum spanning forest under random keys, or with `ranked` by increasing
// Graph::rank and by random key within a rank, ties by edge id: every seed's tree is that
// of Kruskal over a random permutation. Found by Borůvka rounds, each of which adds every
// tree's lightest edge (always in the minimum forest) and contracts the trees to nodes,
// until no edge joins two trees: on a mesh about a quarter of the nodes are left after
// each round, and half the edges. Every pass is parallel, and the first reads the edges
// in their own order (neighbouring faces have nearby ids), where Kruskal would sort them
// and then run a serial union-find over nodes in random order. With distinct weights the
// minimum forest is unique, so it is Kruskal's. With `count_all` an edge's random key is
// drawn for its id; without, for its place among the edges that join two nodes, as if
// the absent edges and self loops were not listed.
std::vector<uint8_t> minimum_forest(const EdgeTable& g, uint64_t seed, bool ranked, bool count_all) {
  const size_t m = size_t(g.num_edges);
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
  std::vector<int32_t> number; // empty: an edge is its own number
  if (!count_all) {
    const auto joins = [&](int32_t e) {
      const auto [u, v] = g.ends(e);
      return u != v;
    };
    const auto at = chunk_offsets(g.num_edges, [&](int32_t begin, int32_t end) {
      int32_t count = 0;
      for (int32_t e = begin; e < end; ++e) count += joins(e);
      return count;
    });
    if (size_t(at.back()) < m) {
      number.resize(m);
      for_chunks(g.num_edges, [&](int32_t c, int32_t begin, int32_t end) {
        for (int32_t e = begin, next = at[size_t(c)]; e < end; ++e) number[size_t(e)] = joins(e) ? next++ : -1;
      });
    }
  }
  const auto key = [&](int32_t e) {
    const uint64_t n = uint64_t(number.empty() ? e : number[size_t(e)]);
    const uint32_t random = uint32_t(Random(salt ^ (n * 0xd1b54a32d192ed03ULL)).next() >> 32);
    return ranked ? uint32_t(g.rank[size_t(e)]) << rank_shift | random >> (32 - rank_shift) : random;
  };
  std::vector<uint8_t> in_forest(m, 0);
  std::vector<int32_t> label;
  const GraphEdges<decltype(key)> edges{g, key};
  int32_t trees = boruvka_round(g.num_nodes, edges, label, in_forest);
  std::vector<TreeEdge> left = edges_between_trees(edges, label);
  // The first round's labels are read no more, and the later rounds' are a quarter as
  // many: their memory goes before the second round, the run's peak on the 10M sphere.
  std::vector<int32_t>().swap(label);
  while (!left.empty()) {
    const TreeEdges<decltype(key)> between{left, key};
    trees = boruvka_round(trees, between, label, in_forest);
    keep_edges_between_trees(left, label);
  }
  return in_forest;
}

// Nodes in a rotated order starting at a random node: the first node of each component
// in this order is its root, so the seed moves the roots without a pass to find the
// components first.
struct RotatedNodes {
  int32_t n, offset;
  RotatedNodes(int32_t count, Random& rng) : n(count), offset(count > 0 ? int32_t(rng.below(uint32_t(count))) : 0) {}
  int32_t operator[](int32_t i) const { return i + offset < n ? i + offset : i + offset - n; }
};

std::vector<int32_t> breadth_first(const EdgeTable& g, Random& rng) {
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

// A depth-first walk (long snakes, few leaves) in which, with probability `branches`, the
// node it stands on first takes all its neighbours still outside the tree as children:
// those it does not walk on from are leaves, so the more often, the more short branches.
// Each node scans its neighbours once, starting at a random offset, so the walk turns
// differently for each seed while the total work stays linear.
std::vector<int32_t> depth_first(const EdgeTable& g, Random& rng, double branches = 0) {
  const Adjacency a = build_adjacency(g);
  const RotatedNodes nodes(g.num_nodes, rng);
  std::vector<uint8_t> seen(size_t(g.num_nodes), 0);
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
      // No draw at 0, so that the plain walk's trees stay what they were.
      const bool all = branches > 0 && rng.unit() < branches;
      do {
        const int32_t k = a.start[size_t(u)] + (offset[size_t(u)] + scanned[size_t(u)]++) % a.degree(u);
        const auto [n, e] = a.adjacent[size_t(k)];
        if (seen[size_t(n)]) continue;
        forest.push_back(e);
        enter(n);
        if (!all) break;
      } while (scanned[size_t(u)] < a.degree(u));
    }
  }
  return forest;
}

// Wilson's algorithm: loop-erased random walks from each node until they hit the tree.
// The walk remembers only the last edge it left each node by, which erases loops.
std::vector<int32_t> wilson(const EdgeTable& g, Random& rng) {
  const Adjacency a = build_adjacency(g);
  // Each component needs a root before walks start, or a walk in it would never end;
  // which node does not change the distribution of the tree. Components by union-find
  // in edge order, which is cache-friendly.
  const RotatedNodes nodes(g.num_nodes, rng);
  std::vector<uint8_t> in_tree(size_t(g.num_nodes), 0);
  {
    UnionFind components(g.num_nodes);
    for (int32_t e = 0; e < g.num_edges; ++e)
      if (const auto [u, v] = g.ends(e); u != v) components.unite(u, v);
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

// spanning_forest; `count_all` as for minimum_forest; `branches` set: depth_first with them.
std::vector<int32_t> forest_of(const EdgeTable& graph, TreeStrategy strategy, uint64_t seed, bool count_all,
                               std::optional<double> branches = std::nullopt) {
  const size_t m = size_t(graph.num_edges);
  // Increasing order through a mark per edge: linear, unlike sorting, and parallel (each
  // edge is marked once). The minimum forest marks its edges as it finds them.
  std::vector<uint8_t> in_forest;
  if (!branches && (strategy == TreeStrategy::random || strategy == TreeStrategy::shaped)) {
    in_forest = minimum_forest(graph, seed, strategy == TreeStrategy::shaped, count_all);
  } else {
    Random rng(seed);
    const std::vector<int32_t> forest = branches                             ? depth_first(graph, rng, *branches)
                                        : strategy == TreeStrategy::uniform ? wilson(graph, rng)
                                        : strategy == TreeStrategy::bfs     ? breadth_first(graph, rng)
                                                                            : depth_first(graph, rng);
    in_forest.assign(m, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, forest.size(), 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) in_forest[size_t(forest[i])] = 1;
    });
  }
  const auto at = chunk_offsets(int32_t(m), [&](int32_t begin, int32_t end) {
    return int32_t(std::count(in_forest.begin() + begin, in_forest.begin() + end, 1));
  });
  std::vector<int32_t> forest(size_t(at.back()));
  for_chunks(int32_t(m), [&](int32_t c, int32_t begin, int32_t end) {
    for (int32_t e = begin, next = at[size_t(c)]; e < end; ++e)
      if (in_forest[size_t(e)]) forest[size_t(next++)] = e;
  });
  return forest;
}

} // namespace

std::vector<int32_t> spanning_forest(const EdgeTable& graph, TreeStrategy strategy, uint64_t seed) {
  return forest_of(graph, strategy, seed, false);
}

std::vector<int32_t> branching_forest(const EdgeTable& graph, double branches, uint64_t seed) {
  if (!(branches >= 0 && branches <= 1)) throw ParameterError("branches", " must be a number from 0 to 1");
  return forest_of(graph, TreeStrategy::random, seed, false, branches);
}

int64_t count_leaves(const EdgeTable& graph, std::span<const int32_t> forest) {
  std::vector<uint8_t> degree(size_t(graph.num_nodes), 0); // saturating at 2: only 1 matters
  for (const int32_t e : forest)
    for (const int32_t n : graph.ends(e))
      if (degree[size_t(n)] < 2) ++degree[size_t(n)];
  return std::count(degree.begin(), degree.end(), uint8_t(1));
}

std::vector<int32_t> spanning_forest(const Graph& graph, TreeStrategy strategy, uint64_t seed) {
  static_assert(sizeof(std::array<int32_t, 2>) == 2 * sizeof(int32_t), "the edges must be rows of two");
  return forest_of(EdgeTable{.num_nodes = graph.num_nodes,
                             .num_edges = int32_t(graph.edges.size()),
                             .rows = graph.edges.empty() ? nullptr : graph.edges[0].data(),
                             .rank = graph.rank},
                   strategy, seed, true);
}

} // namespace meander
