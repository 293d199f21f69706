// A bounding volume hierarchy over the boxes of triangles, for the printability check:
// every pair of triangles whose boxes overlap. Internal to the library.
#pragma once

#include "meander/mesh.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace meander {

class TriangleBvh {
public:
  struct Box {
    float lo[3] = {INFINITY, INFINITY, INFINITY};
    float hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    void extend(Vec3 p) {
      const float c[3] = {p.x, p.y, p.z};
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], c[k]);
        hi[k] = std::max(hi[k], c[k]);
      }
    }
    void extend(const Box& b) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], b.lo[k]);
        hi[k] = std::max(hi[k], b.hi[k]);
      }
    }
    // Closed boxes: touching counts, so that touching triangles are tested.
    bool overlaps(const Box& b) const {
      return lo[0] <= b.hi[0] && b.lo[0] <= hi[0] && lo[1] <= b.hi[1] && b.lo[1] <= hi[1] && lo[2] <= b.hi[2] &&
             b.lo[2] <= hi[2];
    }
  };

  struct Node {
    Box box;
    int32_t first = 0; // leaf: first item; inner node: left child (the right one follows)
    int32_t count = 0; // items of a leaf; 0 for an inner node
  };

  // A linear BVH: the triangles sorted along a Morton curve through their box centres
  // (a 2^10 grid per axis, radix sort), split where the codes first differ, leaves of at
  // most 4; steps and subtrees in parallel (oneTBB). O(n) time and about 40 bytes of
  // memory per triangle (a triangle's box is recomputed rather than stored twice: on
  // large meshes fresh memory is what costs most).
  TriangleBvh(std::span<const Vec3> positions, std::span<const std::array<int32_t, 3>> triangles);

  // Calls f(i, j) once for every unordered pair of distinct triangles i, j whose boxes overlap, from
  // several threads at once and in no particular order: a descent of the tree against
  // itself, so that each pair is met once and disjoint subtrees are dismissed whole.
  template <class F> void for_each_overlapping_pair(F&& f) const {
    if (!nodes_.empty()) within(0, 0, f);
  }

  // Calls f(i) for every triangle i whose box overlaps `box`, on the calling thread.
  template <class F> void for_each_overlapping(const Box& box, F&& f) const {
    if (nodes_.empty() || !nodes_[0].box.overlaps(box)) return;
    int32_t stack[128], top = 0; // depth: 30 Morton bits, then halvings of at most 2^31 items
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[size_t(stack[--top])];
      if (node.count > 0) {
        for (int32_t a = node.first; a < node.first + node.count; ++a)
          if (item_boxes_[size_t(a)].overlaps(box)) f(items_[size_t(a)]);
        continue;
      }
      for (const int32_t child : {node.first, node.first + 1})
        if (nodes_[size_t(child)].box.overlaps(box)) stack[top++] = child;
    }
  }

private:
  // Above this depth the descent forks (a few thousand tasks at most); below it the
  // work per task is too small to pay for a fork.
  static constexpr int kForkDepth = 11;

  template <class F> void within(int32_t n, int depth, F& f) const {
    const Node& node = nodes_[size_t(n)];
    if (node.count > 0) {
      for (int32_t a = node.first; a < node.first + node.count; ++a)
        for (int32_t b = a + 1; b < node.first + node.count; ++b)
          if (item_boxes_[size_t(a)].overlaps(item_boxes_[size_t(b)])) f(items_[size_t(a)], items_[size_t(b)]);
      return;
    }
    const int32_t left = node.first, right = node.first + 1;
    if (depth < kForkDepth)
      tbb::parallel_invoke([&] { within(left, depth + 1, f); }, [&] { within(right, depth + 1, f); },
                           [&] { between(left, right, depth + 1, f); });
    else {
      within(left, depth + 1, f);
      within(right, depth + 1, f);
      between(left, right, depth + 1, f);
    }
  }

  template <class F> void between(int32_t m, int32_t n, int depth, F& f) const {
    const Node& a = nodes_[size_t(m)];
    const Node& b = nodes_[size_t(n)];
    if (!a.box.overlaps(b.box)) return;
    if (a.count > 0 && b.count > 0) {
      for (int32_t i = a.first; i < a.first + a.count; ++i) {
        const Box& box = item_boxes_[size_t(i)];
        if (!box.overlaps(b.box)) continue;
        for (int32_t j = b.first; j < b.first + b.count; ++j)
          if (box.overlaps(item_boxes_[size_t(j)])) f(items_[size_t(i)], items_[size_t(j)]);
      }
      return;
    }
    // Open the node that is not a leaf, the larger one when both are not.
    const bool open_a = b.count > 0 || (a.count == 0 && size(a.box) >= size(b.box));
    if (open_a) {
      fork(depth, [&] { between(a.first, n, depth + 1, f); }, [&] { between(a.first + 1, n, depth + 1, f); });
    } else {
      fork(depth, [&] { between(m, b.first, depth + 1, f); }, [&] { between(m, b.first + 1, depth + 1, f); });
    }
  }

  template <class A, class B> static void fork(int depth, const A& first, const B& second) {
    if (depth < kForkDepth) tbb::parallel_invoke(first, second);
    else {
      first();
      second();
    }
  }

  static float size(const Box& b) { return (b.hi[0] - b.lo[0]) + (b.hi[1] - b.lo[1]) + (b.hi[2] - b.lo[2]); }

  std::vector<Node> nodes_;
  std::vector<int32_t> items_;
  std::vector<Box> item_boxes_; // the box of each entry of items_, in leaf order
};

} // namespace meander
