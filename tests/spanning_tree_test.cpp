#include "meander/spanning_tree.h"

#include "meander/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>

namespace meander {
namespace {

// A grid graph of w x h nodes plus a separate triangle: two components.
Graph grid_and_triangle(int w, int h) {
  Graph g;
  g.num_nodes = w * h + 3;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) g.edges.push_back({y * w + x, y * w + x + 1});
      if (y + 1 < h) g.edges.push_back({y * w + x, (y + 1) * w + x});
    }
  const int t = w * h;
  g.edges.push_back({t, t + 1});
  g.edges.push_back({t + 1, t + 2});
  g.edges.push_back({t + 2, t});
  g.edges.push_back({t, t}); // a self loop must be ignored
  g.edges.push_back({t, t + 1}); // and a repeated edge must not form a cycle
  return g;
}

// Union-find free check: a forest has no cycle iff |edges| = |nodes| - |components| and it
// connects every component.
void expect_spanning_forest(const Graph& g, const std::vector<int32_t>& forest, int components) {
  ASSERT_EQ(int(forest.size()), g.num_nodes - components);
  std::vector<int32_t> label(size_t(g.num_nodes));
  std::iota(label.begin(), label.end(), 0);
  // Relabel until stable (quadratic but tiny graphs).
  for (bool changed = true; changed;) {
    changed = false;
    for (int32_t e : forest) {
      auto [u, v] = g.edges[size_t(e)];
      ASSERT_NE(u, v);
      const int32_t m = std::min(label[size_t(u)], label[size_t(v)]);
      if (label[size_t(u)] != m || label[size_t(v)] != m) changed = true;
      label[size_t(u)] = label[size_t(v)] = m;
    }
  }
  std::sort(label.begin(), label.end());
  EXPECT_EQ(std::unique(label.begin(), label.end()) - label.begin(), components);
  EXPECT_TRUE(std::is_sorted(forest.begin(), forest.end()));
}

// The reference minimum spanning forest by rank: Kruskal over the edges sorted by rank,
// ties by id, in a union-find without balancing (tiny graphs).
std::vector<int32_t> kruskal_by_rank(const Graph& g) {
  std::vector<int32_t> order(g.edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return g.rank[size_t(a)] < g.rank[size_t(b)]; });
  std::vector<int32_t> label(size_t(g.num_nodes));
  std::iota(label.begin(), label.end(), 0);
  auto root = [&](int32_t x) {
    while (label[size_t(x)] != x) x = label[size_t(x)];
    return x;
  };
  std::vector<int32_t> forest;
  for (int32_t e : order)
    if (const int32_t a = root(g.edges[size_t(e)][0]), b = root(g.edges[size_t(e)][1]); a != b) {
      label[size_t(a)] = b;
      forest.push_back(e);
    }
  return forest;
}

// The sum of the ranks of a forest's edges.
int rank_weight(const Graph& g, const std::vector<int32_t>& forest) {
  int total = 0;
  for (int32_t e : forest) total += g.rank[size_t(e)];
  return total;
}

TEST(SpanningTree, EveryStrategySpansEveryComponent) {
  const Graph g = grid_and_triangle(12, 9);
  for (TreeStrategy s : {TreeStrategy::random, TreeStrategy::uniform, TreeStrategy::bfs, TreeStrategy::dfs, TreeStrategy::shaped})
    for (uint64_t seed : {1, 2, 99}) {
      SCOPED_TRACE(std::string(to_string(s)) + " seed " + std::to_string(seed));
      expect_spanning_forest(g, spanning_forest(g, s, seed), 2);
    }
}

// The styles differ measurably: a DFS tree is made of long snakes (a long longest path),
// a BFS tree of short branches around its root (longest path at most twice the radius).
TEST(SpanningTree, DfsMakesSnakesAndBfsMakesShortBranches) {
  Graph g;
  const int n = 40;
  g.num_nodes = n * n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if (x + 1 < n) g.edges.push_back({y * n + x, y * n + x + 1});
      if (y + 1 < n) g.edges.push_back({y * n + x, (y + 1) * n + x});
    }
  // The longest path of a tree: the farthest node from the farthest node of any node.
  auto longest_path = [&](TreeStrategy s) {
    std::vector<std::vector<int32_t>> adj(size_t(g.num_nodes));
    for (int32_t e : spanning_forest(g, s, 3)) {
      adj[size_t(g.edges[size_t(e)][0])].push_back(g.edges[size_t(e)][1]);
      adj[size_t(g.edges[size_t(e)][1])].push_back(g.edges[size_t(e)][0]);
    }
    auto farthest = [&](int32_t from, int& distance) {
      std::vector<int> d(size_t(g.num_nodes), -1);
      std::vector<int32_t> queue{from};
      d[size_t(from)] = 0;
      for (size_t i = 0; i < queue.size(); ++i)
        for (int32_t m : adj[size_t(queue[i])])
          if (d[size_t(m)] < 0) {
            d[size_t(m)] = d[size_t(queue[i])] + 1;
            queue.push_back(m);
          }
      distance = d[size_t(queue.back())];
      return queue.back();
    };
    int distance = 0;
    farthest(farthest(0, distance), distance);
    return distance;
  };
  EXPECT_LE(longest_path(TreeStrategy::bfs), 4 * n);
  EXPECT_GT(longest_path(TreeStrategy::dfs), 3 * longest_path(TreeStrategy::bfs));
}

// branching_forest spans every component for any waviness, is the same for the same
// seed, and has more leaves the higher `branches`: a few seeds' totals grow steadily from
// 0 (the depth-first tree) to 1 on a grid.
TEST(SpanningTree, BranchesSetHowManyLeaves) {
  const Graph g = grid_and_triangle(30, 30);
  const EdgeTable table{.num_nodes = g.num_nodes, .num_edges = int32_t(g.edges.size()), .rows = g.edges[0].data()};
  int64_t previous = 0;
  for (const double branches : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    SCOPED_TRACE(branches);
    int64_t leaves = 0;
    for (uint64_t seed : {1, 2, 3}) {
      const std::vector<int32_t> forest = branching_forest(table, branches, seed);
      expect_spanning_forest(g, forest, 2);
      EXPECT_EQ(forest, branching_forest(table, branches, seed));
      leaves += count_leaves(table, forest);
    }
    EXPECT_GT(leaves, previous);
    previous = leaves;
  }
  // No branches: the depth-first walk.
  EXPECT_EQ(branching_forest(table, 0, 5), spanning_forest(table, TreeStrategy::dfs, 5));
  // A path's two ends are its leaves.
  const Graph path{.num_nodes = 4, .edges = {{0, 1}, {1, 2}, {2, 3}}};
  const EdgeTable path_table{.num_nodes = 4, .num_edges = 3, .rows = path.edges[0].data()};
  EXPECT_EQ(count_leaves(path_table, std::vector<int32_t>{0, 1, 2}), 2);
  for (const double bad : {-0.1, 1.1, double(NAN)}) EXPECT_THROW(branching_forest(table, bad, 1), ParameterError) << bad;
}

// The minimum forests depend on the edges' ids and ranks, not on how the nodes are
// numbered: a grid whose edges come in its nodes' order and the same grid with its nodes
// scattered (most lowerings then go through the second pass of the rounds, past the
// share a chunk keeps aside) give the same forest.
TEST(SpanningTree, MinimumForestIgnoresTheNodesNumbering) {
  const int32_t w = 1024, h = 600;
  Graph g = grid_and_triangle(w, h);
  for (size_t e = 0; e < g.edges.size(); ++e) g.rank.push_back(uint8_t((e * 7919) % 13 % 4));
  std::vector<int32_t> scattered(size_t(g.num_nodes));
  std::iota(scattered.begin(), scattered.end(), 0);
  uint64_t state = 12345;
  for (size_t i = scattered.size() - 1; i > 0; --i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    std::swap(scattered[i], scattered[size_t((state >> 33) % (i + 1))]);
  }
  Graph renumbered = g;
  for (auto& [u, v] : renumbered.edges) {
    u = scattered[size_t(u)];
    v = scattered[size_t(v)];
  }
  for (TreeStrategy s : {TreeStrategy::random, TreeStrategy::shaped})
    for (uint64_t seed : {1, 2}) {
      const std::vector<int32_t> forest = spanning_forest(g, s, seed);
      EXPECT_EQ(forest.size(), size_t(g.num_nodes - 2)); // grid and triangle: two trees
      EXPECT_EQ(spanning_forest(renumbered, s, seed), forest) << to_string(s) << " seed " << seed;
    }
}

// A graph read in place from wider rows, with a bias, absent edges and a self loop, gives
// the forest of the Graph of its edges that join two nodes, whatever the strategy.
TEST(SpanningTree, EdgeTableGivesTheForestOfItsJoiningEdges) {
  const Graph g = grid_and_triangle(30, 20);
  constexpr int32_t bias = 7;
  std::vector<std::array<int32_t, 4>> rows;
  std::vector<uint8_t> rank;
  Graph joining{.num_nodes = g.num_nodes, .edges = {}, .rank = {}};
  std::vector<int32_t> row_of_joining;
  for (size_t e = 0; e < g.edges.size(); ++e) {
    const auto [u, v] = g.edges[e];
    const uint8_t r = uint8_t((e * 7919) % 5);
    rows.push_back({-5, v + bias, 99, u + bias});
    rank.push_back(r);
    if (u != v) {
      joining.edges.push_back(g.edges[e]);
      joining.rank.push_back(r);
      row_of_joining.push_back(int32_t(rows.size()) - 1);
    }
    if (e % 3 == 0) { // an absent edge
      rows.push_back({0, e % 2 ? -1 : u + bias, 0, e % 2 ? v + bias : -1});
      rank.push_back(uint8_t(e % 7));
    }
  }
  const EdgeTable table{.num_nodes = g.num_nodes, .num_edges = int32_t(rows.size()), .rows = rows[0].data(),
                        .stride = 4, .first = 3, .second = 1, .bias = bias, .rank = rank};
  for (TreeStrategy s : {TreeStrategy::random, TreeStrategy::shaped, TreeStrategy::uniform, TreeStrategy::bfs, TreeStrategy::dfs}) {
    SCOPED_TRACE(std::string(to_string(s)));
    std::vector<int32_t> expected;
    for (int32_t e : spanning_forest(joining, s, 5)) expected.push_back(row_of_joining[size_t(e)]);
    EXPECT_EQ(spanning_forest(table, s, 5), expected);
  }
  expect_spanning_forest(joining, spanning_forest(joining, TreeStrategy::random, 5), 2);
}

// Kruskal by rank gives a minimum spanning forest for the ranks as weights; within a rank
// the order is random, so seeds still differ.
TEST(SpanningTree, ShapedTreeIsAMinimumSpanningForestByRank) {
  Graph g = grid_and_triangle(20, 15);
  for (size_t e = 0; e < g.edges.size(); ++e) g.rank.push_back(uint8_t((e * 7919) % 5));
  auto weight = [&](const std::vector<int32_t>& forest) { return rank_weight(g, forest); };
  const std::vector<int32_t> reference = kruskal_by_rank(g);
  const std::vector<int32_t> one = spanning_forest(g, TreeStrategy::shaped, 1), two = spanning_forest(g, TreeStrategy::shaped, 2);
  expect_spanning_forest(g, one, 2);
  EXPECT_EQ(weight(one), weight(reference));
  EXPECT_EQ(weight(two), weight(reference));
  EXPECT_NE(one, two);
  EXPECT_GT(weight(spanning_forest(g, TreeStrategy::random, 1)), weight(reference));
  g.rank.pop_back();
  EXPECT_THROW(spanning_forest(g, TreeStrategy::shaped, 1), UsageError);
}

// The random tree is the minimum spanning tree of independent random weights, found by
// Borůvka rounds: on a cycle that tree leaves out the heaviest edge, each edge equally
// often. A round that favoured low ids, or keys that depended on the order of the passes,
// would skew the counts. 6000 seeds: each count is 1000 on average with a standard
// deviation of 29, so the bounds are 5 deviations wide.
TEST(SpanningTree, RandomTreeOnACycleLeavesOutEachEdgeEquallyOften) {
  Graph g;
  g.num_nodes = 6;
  for (int32_t i = 0; i < 6; ++i) g.edges.push_back({i, (i + 1) % 6});
  for (const TreeStrategy s : {TreeStrategy::random, TreeStrategy::shaped}) {
    SCOPED_TRACE(std::string(to_string(s)));
    std::array<int, 6> left_out{};
    for (uint64_t seed = 1; seed <= 6000; ++seed) {
      const std::vector<int32_t> forest = spanning_forest(g, s, seed);
      ASSERT_EQ(forest.size(), 5u);
      int32_t missing = 0;
      while (missing < 5 && forest[size_t(missing)] == missing) ++missing;
      ++left_out[size_t(missing)];
    }
    for (int e = 0; e < 6; ++e) {
      EXPECT_GT(left_out[size_t(e)], 855) << "edge " << e;
      EXPECT_LT(left_out[size_t(e)], 1145) << "edge " << e;
    }
  }
}

// A large graph takes the rounds in parallel over many threads' worth of nodes. Disjoint
// 6-cycles make one in which every cycle repeats the test above: the random forest leaves
// out each of a cycle's edges equally often (about 58,000 times each, standard deviation
// 220), and the shaped one an edge of the cycle's highest rank, as a minimum spanning
// forest must.
TEST(SpanningTree, BoruvkaRoundsKeepTheForestOfARandomOrder) {
  const int32_t cycles = (1 << 21) / 6 + 1;
  Graph g;
  g.num_nodes = 6 * cycles;
  for (int32_t c = 0; c < cycles; ++c)
    for (int32_t i = 0; i < 6; ++i) g.edges.push_back({6 * c + i, 6 * c + (i + 1) % 6});
  for (size_t e = 0; e < g.edges.size(); ++e) g.rank.push_back(uint8_t((e * 7919) % 11 % 3));
  // The edge each cycle leaves out, by its place in the cycle.
  auto left_out = [&](const std::vector<int32_t>& forest) {
    EXPECT_EQ(forest.size(), 5 * size_t(cycles));
    std::vector<int> missing(size_t(cycles), -1);
    std::vector<uint8_t> in_forest(g.edges.size(), 0);
    for (int32_t e : forest) in_forest[size_t(e)] = 1;
    for (size_t e = 0; e < g.edges.size(); ++e)
      if (!in_forest[e]) {
        EXPECT_EQ(missing[e / 6], -1) << "cycle " << e / 6 << " lost two edges";
        missing[e / 6] = int(e % 6);
      }
    return missing;
  };
  std::array<int, 6> count{};
  for (int place : left_out(spanning_forest(g, TreeStrategy::random, 7))) ++count[size_t(place)];
  for (int place = 0; place < 6; ++place) EXPECT_NEAR(count[size_t(place)], cycles / 6.0, 1500) << "place " << place;
  const std::vector<int> shaped = left_out(spanning_forest(g, TreeStrategy::shaped, 7));
  for (int32_t c = 0; c < cycles; ++c) {
    uint8_t highest = 0;
    for (int i = 0; i < 6; ++i) highest = std::max(highest, g.rank[6 * size_t(c) + size_t(i)]);
    ASSERT_EQ(g.rank[6 * size_t(c) + size_t(shaped[size_t(c)])], highest) << "cycle " << c;
  }
}

// Borůvka's later rounds run on the edges left between trees: many of them join the
// same two trees, and each round must keep only ones that join different trees. On a
// random multigraph with repeated edges and self loops (several components, many rounds)
// the shaped forest must still weigh what Kruskal's by rank weighs, for every seed.
TEST(SpanningTree, ShapedTreeIsMinimalOnAMultigraph) {
  Graph g;
  g.num_nodes = 3000;
  uint64_t state = 12345;
  const auto next = [&](int32_t below) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return int32_t((state >> 33) % uint64_t(below));
  };
  for (int e = 0; e < 9000; ++e) {
    const int32_t u = next(2900), v = next(8) == 0 ? u : next(2900); // nodes 2900.. stay alone
    g.edges.push_back({u, v});
    if (next(4) == 0) g.edges.push_back({v, u});
  }
  for (size_t e = 0; e < g.edges.size(); ++e) g.rank.push_back(uint8_t(next(Graph::max_rank)));
  const std::vector<int32_t> reference = kruskal_by_rank(g);
  const int32_t joined = int32_t(reference.size());
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::vector<int32_t> forest = spanning_forest(g, TreeStrategy::shaped, seed);
    expect_spanning_forest(g, forest, g.num_nodes - joined);
    EXPECT_EQ(rank_weight(g, forest), rank_weight(g, reference));
    expect_spanning_forest(g, spanning_forest(g, TreeStrategy::random, seed), g.num_nodes - joined);
  }
}

TEST(SpanningTree, ParsesNamesAndRefusesOthers) {
  EXPECT_EQ(parse_tree_strategy("uniform"), TreeStrategy::uniform);
  EXPECT_EQ(to_string(parse_tree_strategy("dfs")), "dfs");
  EXPECT_EQ(to_string(parse_tree_strategy("shaped")), "shaped");
  try {
    parse_tree_strategy("prim");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "unknown tree strategy 'prim' (expected random, uniform, bfs, dfs or shaped)");
  }
}

} // namespace
} // namespace meander
