// A bounding volume hierarchy over boxes (of triangles, in practice), for the
// printability check: which boxes overlap a box, and the nearest hit along a ray.
// Internal to the library.
#pragma once

#include "meander/mesh.h"

#include <algorithm>
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

  // Top-down median splits along the longest axis of the box centres, leaves of at most
  // 4 boxes; subtrees are built in parallel (oneTBB). O(n log n).
  explicit TriangleBvh(std::span<const Box> boxes);

  // Calls f(i) for every box i that overlaps `query`.
  template <class F> void for_each_overlap(const Box& query, F&& f) const {
    if (nodes_.empty()) return;
    int32_t stack[64];
    int32_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[size_t(stack[--top])];
      if (!node.box.overlaps(query)) continue;
      if (node.count > 0) {
        for (int32_t k = node.first; k < node.first + node.count; ++k) f(items_[size_t(k)]);
      } else {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
  }

  // The nearest hit along the ray origin + t * direction, t > 0: hit(i, t_max) tests box
  // i's item and returns the smaller of t_max and its hit distance. Returns the nearest
  // t, or infinity.
  template <class P, class F> double cast(const P& origin, const P& direction, F&& hit) const {
    double t_max = INFINITY;
    if (nodes_.empty()) return t_max;
    const double o[3] = {origin.x, origin.y, origin.z};
    const double d[3] = {direction.x, direction.y, direction.z};
    // Slab test: where the ray enters the box (t >= 0), or infinity if it misses it or
    // enters beyond t_max.
    const auto entry = [&](const Box& b) {
      double t0 = 0, t1 = t_max;
      for (int k = 0; k < 3; ++k) {
        if (d[k] == 0) {
          if (o[k] < b.lo[k] || o[k] > b.hi[k]) return double(INFINITY);
          continue;
        }
        double a = (b.lo[k] - o[k]) / d[k], c = (b.hi[k] - o[k]) / d[k];
        if (a > c) std::swap(a, c);
        t0 = std::max(t0, a);
        t1 = std::min(t1, c);
      }
      return t0 <= t1 ? t0 : double(INFINITY);
    };
    int32_t stack[64];
    int32_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[size_t(stack[--top])];
      if (entry(node.box) == INFINITY) continue;
      if (node.count > 0) {
        for (int32_t k = node.first; k < node.first + node.count; ++k) t_max = hit(items_[size_t(k)], t_max);
        continue;
      }
      // Nearer child last on the stack, so it is visited first and shrinks t_max.
      const double near_left = entry(nodes_[size_t(node.first)].box);
      const double near_right = entry(nodes_[size_t(node.first) + 1].box);
      if (near_left <= near_right) {
        if (near_right != INFINITY) stack[top++] = node.first + 1;
        if (near_left != INFINITY) stack[top++] = node.first;
      } else {
        if (near_left != INFINITY) stack[top++] = node.first;
        if (near_right != INFINITY) stack[top++] = node.first + 1;
      }
    }
    return t_max;
  }

private:
  std::vector<Node> nodes_;
  std::vector<int32_t> items_;
};

} // namespace meander
