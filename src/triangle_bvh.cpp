#include "triangle_bvh.h"

#include <tbb/parallel_invoke.h>

#include <atomic>

namespace meander {
namespace {

constexpr int32_t kLeafSize = 4;
// Below this many boxes a subtree is built on the calling thread: spawning costs more.
constexpr int32_t kParallelGrain = 1 << 12;

struct Builder {
  std::span<const TriangleBvh::Box> boxes;
  std::vector<float> centre; // 3 per box, twice the centre (no halving needed to compare)
  std::vector<int32_t>& items;
  std::vector<TriangleBvh::Node>& nodes;
  std::atomic<int32_t> next_node{1};

  void build(int32_t node, int32_t begin, int32_t end) {
    TriangleBvh::Box box, centres;
    for (int32_t k = begin; k < end; ++k) {
      const int32_t i = items[size_t(k)];
      box.extend(boxes[size_t(i)]);
      centres.extend(Vec3{centre[3 * size_t(i)], centre[3 * size_t(i) + 1], centre[3 * size_t(i) + 2]});
    }
    nodes[size_t(node)].box = box;
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis]) axis = k;
    // A leaf when small, or when every centre is the same point (no split separates them).
    if (end - begin <= kLeafSize || centres.hi[axis] == centres.lo[axis]) {
      nodes[size_t(node)].first = begin;
      nodes[size_t(node)].count = end - begin;
      return;
    }
    const int32_t middle = begin + (end - begin) / 2;
    std::nth_element(items.begin() + begin, items.begin() + middle, items.begin() + end, [&](int32_t a, int32_t b) {
      const float ca = centre[3 * size_t(a) + size_t(axis)], cb = centre[3 * size_t(b) + size_t(axis)];
      return ca < cb || (ca == cb && a < b);
    });
    const int32_t left = next_node.fetch_add(2);
    nodes[size_t(node)].first = left;
    nodes[size_t(node)].count = 0;
    if (end - begin > kParallelGrain)
      tbb::parallel_invoke([&] { build(left, begin, middle); }, [&] { build(left + 1, middle, end); });
    else {
      build(left, begin, middle);
      build(left + 1, middle, end);
    }
  }
};

} // namespace

TriangleBvh::TriangleBvh(std::span<const Box> boxes) {
  const int32_t n = int32_t(boxes.size());
  if (n == 0) return;
  items_.resize(size_t(n));
  std::vector<float> centre(3 * size_t(n));
  for (int32_t i = 0; i < n; ++i) {
    items_[size_t(i)] = i;
    for (int k = 0; k < 3; ++k) centre[3 * size_t(i) + size_t(k)] = boxes[size_t(i)].lo[k] + boxes[size_t(i)].hi[k];
  }
  // A binary tree with leaves of at least one box has fewer than 2n nodes.
  nodes_.resize(2 * size_t(n));
  Builder builder{boxes, std::move(centre), items_, nodes_};
  builder.build(0, 0, n);
  nodes_.resize(size_t(builder.next_node.load()));
}

} // namespace meander
