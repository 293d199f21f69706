#include "triangle_bvh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <atomic>
#include <bit>
#include <cmath>

namespace meander {
namespace {

constexpr int32_t kLeafSize = 4;
// Below this many boxes a subtree is built on the calling thread: spawning costs more.
constexpr int32_t kParallelGrain = 1 << 12;
constexpr int kMortonBits = 10; // per axis: 30 bits, leaving the low 32 of a key to the box

// The bits of v (< 2^10) spread out to every third bit.
uint32_t spread(uint32_t v) {
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

// Sorts by the high 32 bits, keeping the order of keys equal there (least significant
// digit first, 8 bits a pass): linear time, and the keys are built in box order, so
// boxes of one Morton cell stay in their input order.
void radix_sort_high_half(std::vector<uint64_t>& keys) {
  std::vector<uint64_t> buffer(keys.size());
  for (int shift = 32; shift < 32 + 3 * kMortonBits; shift += 8) {
    size_t count[257] = {};
    for (const uint64_t k : keys) ++count[((k >> shift) & 0xff) + 1];
    for (int d = 0; d < 256; ++d) count[d + 1] += count[d];
    for (const uint64_t k : keys) buffer[count[(k >> shift) & 0xff]++] = k;
    keys.swap(buffer);
  }
}

// Where the range [begin, end) of sorted Morton codes splits: where the codes first
// differ (Karras 2012, "Maximizing parallelism in the construction of BVHs"), so that each
// half fills a cell of the octree-like grid; a range within one cell is halved in order.
int32_t split(std::span<const uint32_t> codes, int32_t begin, int32_t end) {
  const uint32_t first = codes[size_t(begin)], last = codes[size_t(end - 1)];
  if (first == last) return begin + (end - begin) / 2;
  const uint32_t bit = uint32_t(1) << (31 - std::countl_zero(first ^ last));
  return int32_t(std::partition_point(codes.begin() + begin, codes.begin() + end,
                                      [bit](uint32_t c) { return (c & bit) == 0; }) -
                 codes.begin());
}

// The number of nodes the build makes: it sizes the node array exactly, which for
// millions of boxes costs less than clearing the 2n nodes a bound would need.
int32_t count_nodes(std::span<const uint32_t> codes, int32_t begin, int32_t end) {
  if (end - begin <= kLeafSize) return 1;
  const int32_t middle = split(codes, begin, end);
  if (end - begin <= kParallelGrain) return 1 + count_nodes(codes, begin, middle) + count_nodes(codes, middle, end);
  int32_t a = 0, b = 0;
  tbb::parallel_invoke([&] { a = count_nodes(codes, begin, middle); }, [&] { b = count_nodes(codes, middle, end); });
  return 1 + a + b;
}

struct Builder {
  std::span<const TriangleBvh::Box> boxes; // in leaf order
  std::span<const uint32_t> codes;         // Morton code of each box, in leaf order (sorted)
  std::vector<TriangleBvh::Node>& nodes;
  std::atomic<int32_t> next_node{1};

  // Returns the node's box.
  TriangleBvh::Box build(int32_t node, int32_t begin, int32_t end) {
    TriangleBvh::Node& out = nodes[size_t(node)];
    if (end - begin <= kLeafSize) {
      TriangleBvh::Box box;
      for (int32_t k = begin; k < end; ++k) box.extend(boxes[size_t(k)]);
      out = {box, begin, end - begin};
      return box;
    }
    const int32_t middle = split(codes, begin, end);
    const int32_t left = next_node.fetch_add(2);
    TriangleBvh::Box a, b;
    if (end - begin > kParallelGrain)
      tbb::parallel_invoke([&] { a = build(left, begin, middle); }, [&] { b = build(left + 1, middle, end); });
    else {
      a = build(left, begin, middle);
      b = build(left + 1, middle, end);
    }
    a.extend(b);
    out = {a, left, 0};
    return a;
  }
};

} // namespace

TriangleBvh::TriangleBvh(std::span<const Vec3> positions, std::span<const std::array<int32_t, 3>> triangles) {
  const int32_t n = int32_t(triangles.size());
  if (n == 0) return;
  const auto box_of = [&](int32_t i) {
    Box box;
    for (const int32_t v : triangles[size_t(i)]) box.extend(positions[size_t(v)]);
    return box;
  };
  // Twice the box centres (no halving needed), their box, and a cell of a 2^10 grid over it.
  const auto centre = [](const Box& b, int k) { return b.lo[k] + b.hi[k]; };
  const Box extent = tbb::parallel_reduce(
      tbb::blocked_range<int32_t>(0, n, 1 << 14), Box{},
      [&](const tbb::blocked_range<int32_t>& r, Box box) {
        for (int32_t i = r.begin(); i < r.end(); ++i) {
          const Box b = box_of(i);
          box.extend(Vec3{centre(b, 0), centre(b, 1), centre(b, 2)});
        }
        return box;
      },
      [](Box a, const Box& b) {
        a.extend(b);
        return a;
      });
  float scale[3];
  for (int k = 0; k < 3; ++k) {
    const float size = extent.hi[k] - extent.lo[k];
    // An extent so thin that the scale overflows (a flat wire of a tiny radius) is one
    // cell, as an empty one is: infinity times the 0 of a box at its low side is NaN.
    const float s = float((1 << kMortonBits) - 1) / size;
    scale[k] = size > 0 && std::isfinite(s) ? s : 0;
  }
  std::vector<uint64_t> keys(static_cast<size_t>(n));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, n, 1 << 14), [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t i = r.begin(); i < r.end(); ++i) {
      const Box b = box_of(i);
      uint32_t code = 0;
      for (int k = 0; k < 3; ++k) {
        const uint32_t cell =
            std::min(uint32_t((centre(b, k) - extent.lo[k]) * scale[k]), uint32_t((1 << kMortonBits) - 1));
        code |= spread(cell) << (2 - k);
      }
      keys[size_t(i)] = uint64_t(code) << 32 | uint32_t(i);
    }
  });
  radix_sort_high_half(keys);

  items_.resize(size_t(n));
  item_boxes_.resize(size_t(n));
  std::vector<uint32_t> codes(static_cast<size_t>(n));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, n, 1 << 14), [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t k = r.begin(); k < r.end(); ++k) {
      items_[size_t(k)] = int32_t(keys[size_t(k)] & 0xffffffffu);
      codes[size_t(k)] = uint32_t(keys[size_t(k)] >> 32);
      item_boxes_[size_t(k)] = box_of(items_[size_t(k)]);
    }
  });
  nodes_.resize(size_t(count_nodes(codes, 0, n)));
  Builder builder{item_boxes_, codes, nodes_};
  builder.build(0, 0, n);
}

} // namespace meander
