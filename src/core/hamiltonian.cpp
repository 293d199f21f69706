#include "meander/hamiltonian.h"

#include "chunks.h"
#include "meander/error.h"
#include "random.h"
#include "union_find.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meander {

namespace {

// A triangle is named by its quad and its apex corner. Diagonal 0 (corners 0-2) leaves
// the apexes 1 and 3, diagonal 1 (corners 1-3) the apexes 0 and 2; its two quad sides
// are apex-1 and apex. Its slot 2q + (apex >= 2) indexes per-triangle arrays.
inline int32_t slot(int32_t q, int apex) { return 2 * q + (apex >= 2); }

// The apex of the triangle of quad side `side` under diagonal d.
inline int apex_of_side(int side, uint8_t d) { return (side & 1) != d ? side : (side + 1) & 3; }

// Walks the loop through triangle (q0, a0), leaving it first through side a0, and calls
// visit(q, apex) for each triangle once, starting with (q0, a0).
template <typename Visit>
void walk_loop(const QuadMesh& m, const std::vector<uint8_t>& diagonal, int32_t q0, int a0, Visit&& visit) {
  int32_t q = q0;
  int a = a0, out = a0;
  do {
    visit(q, a);
    const int32_t next = m.neighbors[size_t(q)][size_t(out)];
    q = next >> 2;
    const int in = next & 3;
    a = apex_of_side(in, diagonal[size_t(q)]);
    out = a == in ? (a + 3) & 3 : a;
  } while (q != q0 || a != a0);
}

// In parallel (a pass over all the sides, 45 ms on one core for 10M triangles), naming
// the first open side in quad order.
void require_closed_sides(const QuadMesh& m) {
  std::array<int64_t, kChunks> first;
  first.fill(-1);
  for_chunks(m.num_quads(), [&](int32_t c, int32_t begin, int32_t end) {
    for (int32_t q = begin; q < end && first[size_t(c)] < 0; ++q)
      for (int k = m.is_half(q) ? 2 : 0; k < 4; ++k)
        if (m.neighbors[size_t(q)][size_t(k)] < 0) {
          first[size_t(c)] = 4 * int64_t(q) + k;
          break;
        }
  });
  for (const int64_t side : first)
    if (side >= 0)
      throw TopologyError("quad " + std::to_string(side / 4) + " side " + std::to_string(side % 4) +
                          " lies on a boundary: this quad mesh has boundary edges, and Taubin's cycle "
                          "needs a closed quad mesh (use quad dual-simplest, which handles boundaries)");
}

// How close the triangle (a, b, c) is to equilateral: 4 sqrt(3) area / (sum of squared
// sides), 1 for equilateral, 0 for degenerate.
double triangle_shape(Vec3 a, Vec3 b, Vec3 c) {
  const double squares = dot(b - a, b - a) + dot(c - b, c - b) + dot(a - c, a - c);
  return squares > 0 ? 2 * std::sqrt(3.0) * norm(cross(b - a, c - a)) / squares : 0.0;
}

// The worse shape of quad q's two triangles under diagonal d, negated for a triangle
// that faces against the quad's vector area: a concave quad (a scan's needle moves a
// face centre past the edge's end) split along its outer diagonal folds one triangle
// back over the other, and the curve, the ribbon and the slabs with it.
double split_shape(const QuadMesh& m, int32_t q, uint8_t d) {
  const auto& c = m.quads[size_t(q)];
  auto at = [&](int k) { return m.positions[size_t(c[size_t(k & 3)])]; };
  const Vec3 area = cross(at(2) - at(0), at(3) - at(1));
  auto shape = [&](Vec3 a, Vec3 b, Vec3 e) {
    const double s = triangle_shape(a, b, e);
    return dot(cross(b - a, e - a), area) < 0 ? -s : s;
  };
  return std::min(shape(at(d), at(d + 1), at(d + 2)), shape(at(d + 2), at(d + 3), at(d)));
}

// The shaped tree's rank of flipping quad q from diagonal d: how much the flip improves
// the worse of its triangles (a gain of 1 ranks 0, a loss of 1 ranks 2 * steps), plus a
// dither in [0, 1) from a hash of the quad and the seed, so that quads of about the same
// gain mix at random instead of splitting at a hard threshold. A flip that folds a
// triangle over takes the last rank: the tree uses it only to stay connected.
uint8_t flip_rank(const QuadMesh& m, int32_t q, uint8_t d, uint64_t seed) {
  constexpr double steps = (Graph::max_rank - 1) / 2.0;
  const double flipped = split_shape(m, q, d ^ 1);
  if (flipped < 0) return Graph::max_rank - 1;
  const double gain = flipped - split_shape(m, q, d);
  const double dither = Random(seed ^ (uint64_t(q) * 0xd1b54a32d192ed03ULL)).unit();
  return uint8_t(std::clamp(std::floor(steps * (1 - gain) + dither), 0.0, double(Graph::max_rank - 1)));
}

// Every quad side closed (only half quads end at a boundary) and triangle names within
// an int32.
void require_cycle_size(const QuadMesh& m) {
  require_closed_sides(m);
  if (m.num_quads() >= (1 << 29))
    throw UsageError("the quad mesh has " + std::to_string(m.num_quads()) + " quads; at most 2^29 are supported");
}

// The loops of the triangulation `diagonal` gives, each walked once from its first
// triangle in quad order, told to `observer` as they are walked.
TriangleCycle loops_of(const QuadMesh& m, std::vector<uint8_t> diagonal, const WalkObserver* observer) {
  const int32_t nq = m.num_quads();
  TriangleCycle result;
  result.diagonal = std::move(diagonal);
  // Never more than two triangles a quad: the order's memory never moves, as observers need.
  result.order.reserve(2 * size_t(nq));
  int64_t report_at = observer ? observer->every : std::numeric_limits<int64_t>::max();
  const auto report = [&] {
    observer->seen(result.order, result.cycle_start);
    report_at = int64_t(result.order.size()) + observer->every;
  };
  const auto first_apex = [&](int32_t q) { return m.is_half(q) ? 3 : 1 - result.diagonal[size_t(q)]; };
  const auto walk = [&](int32_t q, int a, auto&& also) {
    walk_loop(m, result.diagonal, q, a, [&](int32_t tq, int ta) {
      also(tq, ta);
      result.order.push_back(4 * tq + ta);
      if (int64_t(result.order.size()) >= report_at) report();
    });
    result.cycle_start.push_back(int32_t(result.order.size()));
  };
  // The first loop is walked without marking its triangles: on a closed mesh of one
  // component, the usual case, it holds all of them, and the marks would cost the walk a
  // store into a second array at every step. Otherwise they are marked afterwards.
  if (nq > 0) walk(0, first_apex(0), [](int32_t, int) {});
  if (result.order.size() < 2 * size_t(nq)) {
    std::vector<uint8_t> visited(2 * size_t(nq), 0);
    for (const int32_t t : result.order) visited[size_t(slot(t >> 2, t & 3))] = 1;
    for (int32_t q = 0; q < nq; ++q)
      for (int a = first_apex(q); a <= 3; a += 2)
        if (!visited[size_t(slot(q, a))]) walk(q, a, [&](int32_t tq, int ta) { visited[size_t(slot(tq, ta))] = 1; });
  }
  if (observer) report();
  return result;
}

} // namespace

TriangleCycle hamiltonian_cycle(const QuadMesh& m, const CycleOptions& options, const WalkObserver* observer) {
  require_cycle_size(m);
  if (options.branches && options.tree != TreeStrategy::random)
    throw ParameterError("branches", " grows a tree of its own, so it combines only with the random tree (the default), not " +
                                         std::string(to_string(options.tree)));
  const int32_t nq = m.num_quads();
  const bool initial = !options.initial_diagonal.empty();
  if (initial && int64_t(options.initial_diagonal.size()) != nq)
    throw UsageError("initial diagonals: " + std::to_string(options.initial_diagonal.size()) + " for " +
                     std::to_string(nq) + " quads");
  std::vector<uint8_t> diagonal(size_t(nq), 0);
  if (initial) diagonal.assign(options.initial_diagonal.begin(), options.initial_diagonal.end());

  // With every quad split along its initial diagonal the triangles form disjoint loops
  // (each triangle has two quad sides, each side two triangles): the nodes of the graph,
  // whose edge q is quad q, joining the loops of its two triangles (absent at a half quad,
  // which has one). The edges are read from where the loops are named, not copied.
  EdgeTable graph{.num_edges = nq};
  std::vector<int32_t> loop;
  if (m.face_point_offset >= 0 && !initial) {
    // Dual of Simplest: the loops are the faces, named by the face points at corners 1
    // and 3 (corner 1 of a half quad is -1).
    static_assert(sizeof(std::array<int32_t, 4>) == 4 * sizeof(int32_t));
    graph.num_nodes = int32_t(m.positions.size()) - m.face_point_offset;
    graph.rows = nq > 0 ? m.quads[0].data() : nullptr;
    graph.stride = 4;
    graph.first = 1;
    graph.second = 3;
    graph.bias = m.face_point_offset;
  } else {
    loop.assign(2 * size_t(nq), -1); // a half quad's first slot stays -1
    for (int32_t q = 0; q < nq; ++q)
      for (int a = m.is_half(q) ? 3 : 1 - diagonal[size_t(q)]; a <= 3; a += 2)
        if (loop[size_t(slot(q, a))] < 0) {
          walk_loop(m, diagonal, q, a, [&](int32_t tq, int ta) { loop[size_t(slot(tq, ta))] = graph.num_nodes; });
          ++graph.num_nodes;
        }
    graph.rows = loop.data();
  }
  // The shaped tree flips first the quads whose flip shapes their triangles better: the
  // variable wire's slabs fold where the cycle crosses a sliver (docs/wires.md).
  std::vector<uint8_t> rank;
  if (options.tree == TreeStrategy::shaped) {
    rank.assign(size_t(nq), 0);
    for (int32_t q = 0; q < nq; ++q)
      if (!m.is_half(q)) rank[size_t(q)] = flip_rank(m, q, diagonal[size_t(q)], options.seed);
    graph.rank = rank;
  }
  // Flipping a quad whose two triangles lie on different loops merges the loops, so
  // flipping the quads of a spanning forest of "loops joined by a quad" leaves one loop
  // per component (ALGORITHM-NOTES). Flips commute: only the final diagonals matter.
  // The forest and the loops' names are freed before the walk lays out its order (114
  // MiB on the 10M sphere, with the quad mesh the largest thing it holds).
  int64_t leaves = -1;
  {
    const std::vector<int32_t> forest = options.branches ? branching_forest(graph, *options.branches, options.seed)
                                                         : spanning_forest(graph, options.tree, options.seed);
    if (options.count_leaves) leaves = count_leaves(graph, forest);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, forest.size(), 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) diagonal[size_t(forest[i])] ^= 1; // each quad once
    });
  }
  std::vector<int32_t>().swap(loop);
  TriangleCycle cycle = loops_of(m, std::move(diagonal), observer);
  cycle.leaves = leaves;
  return cycle;
}

TriangleCycle triangle_loops(const QuadMesh& m, std::vector<uint8_t> diagonal) {
  require_cycle_size(m);
  if (int64_t(diagonal.size()) != m.num_quads())
    throw UsageError("diagonals: " + std::to_string(diagonal.size()) + " for " + std::to_string(m.num_quads()) + " quads");
  return loops_of(m, std::move(diagonal), nullptr);
}

std::string verify_cycle(const QuadMesh& m, const TriangleCycle& cycle) {
  const int32_t nq = m.num_quads();
  if (int32_t(cycle.diagonal.size()) != nq) return "diagonal has " + std::to_string(cycle.diagonal.size()) + " entries for " + std::to_string(nq) + " quads";

  // Each triangle the diagonals make must appear once. Triangles are told apart by their
  // quad and apex, not by their corners: different quads can make triangles with the same
  // three corners (three quads on four vertices close into a projective plane that has
  // them), and such a cycle is still right.
  int64_t triangles = 0;
  for (int32_t q = 0; q < nq; ++q) triangles += m.is_half(q) ? 1 : 2;
  if (triangles != cycle.num_triangles())
    return "the cycles hold " + std::to_string(cycle.num_triangles()) + " triangles but the triangulation has " +
           std::to_string(triangles);
  // Half quads keep only the triangle of apex 3; diagonal 0 leaves apexes 1 and 3, 1 leaves 0 and 2.
  auto made = [&](int32_t q, int apex) { return m.is_half(q) ? apex == 3 : (apex & 1) != cycle.diagonal[size_t(q)]; };
  std::vector<uint8_t> seen(4 * size_t(nq), 0); // by triangle name, 4 * quad + apex
  UnionFind components(nq);
  for (int32_t q = 0; q < nq; ++q)
    for (int32_t n : m.neighbors[size_t(q)])
      if (n >= 0) components.unite(q, n >> 2);

  std::map<int32_t, int32_t> cycle_of_component;
  for (int32_t k = 0; k < cycle.num_cycles(); ++k) {
    const int32_t first = cycle.cycle_start[size_t(k)], last = cycle.cycle_start[size_t(k) + 1];
    if (last - first < 2) return "cycle " + std::to_string(k) + " has fewer than 2 triangles";
    int32_t component = -1;
    for (int32_t i = first; i < last; ++i) {
      const int32_t id = cycle.order[size_t(i)];
      if (id < 0 || (id >> 2) >= nq) return "triangle " + std::to_string(i) + " names no quad";
      if (!made(id >> 2, id & 3)) return "triangle " + std::to_string(i) + " is not a triangle of the triangulation";
      if (seen[size_t(id)]++) return "triangle " + std::to_string(i) + " appears twice";
      const auto t = cycle_triangle(m, id);
      const int32_t c = components.find(id >> 2);
      if (component < 0) component = c;
      if (c != component) return "cycle " + std::to_string(k) + " spans two components";
      const int32_t next = cycle.order[size_t(i + 1 == last ? first : i + 1)];
      if (next < 0 || (next >> 2) >= nq) return "triangle " + std::to_string(i + 1) + " names no quad";
      const auto u = cycle_triangle(m, next);
      int shared = 0;
      for (int32_t a : t) shared += a == u[0] || a == u[1] || a == u[2];
      if (shared < 2)
        return "triangles " + std::to_string(i) + " and " + std::to_string(i + 1 == last ? first : i + 1) +
               " of cycle " + std::to_string(k) + " share no edge";
    }
    if (!cycle_of_component.emplace(component, k).second)
      return "cycles " + std::to_string(cycle_of_component[component]) + " and " + std::to_string(k) +
             " lie in one connected component (a missed merge)";
  }
  return "";
}

PolygonMesh cycle_triangles(const QuadMesh& quads, const TriangleCycle& cycle) {
  PolygonMesh m;
  m.positions = quads.positions;
  m.face_vertices.reserve(cycle.order.size() * 3);
  m.face_start.resize(cycle.order.size() + 1);
  for (size_t t = 0; t < cycle.order.size(); ++t) {
    const auto corners = cycle_triangle(quads, cycle.order[t]);
    m.face_vertices.insert(m.face_vertices.end(), corners.begin(), corners.end());
    m.face_start[t + 1] = int32_t(3 * (t + 1));
  }
  return m;
}

} // namespace meander
