// Disjoint sets over int32 handles: path halving and union by size, so a sequence of
// operations costs near-linear time. Internal to the library.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace meander {

class UnionFind {
public:
  explicit UnionFind(int32_t n) : parent_(size_t(n), -1) {}

  int32_t find(int32_t x) {
    for (int32_t p; (p = parent_[size_t(x)]) >= 0;) {
      const int32_t grandparent = parent_[size_t(p)];
      if (grandparent < 0) return p;
      parent_[size_t(x)] = grandparent;
      x = grandparent;
    }
    return x;
  }

  // Joins the sets of a and b; false if they were already one set.
  bool unite(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (parent_[size_t(a)] > parent_[size_t(b)]) std::swap(a, b); // a's set is the larger
    parent_[size_t(a)] += parent_[size_t(b)];
    parent_[size_t(b)] = a;
    return true;
  }

  // Asks the cache for x's entry ahead of a find, for callers that know their next
  // elements while the current one is still waiting on memory.
  void prefetch(int32_t x) const { __builtin_prefetch(parent_.data() + x); }

  // x stands for its set (find(x) == x), without the cost of a find.
  bool is_root(int32_t x) const { return parent_[size_t(x)] < 0; }

private:
  // One array, so a find touches half the memory of separate parent and size arrays:
  // parent_[x] is x's parent, or minus the size of x's set when x is a root.
  std::vector<int32_t> parent_;
};

} // namespace meander
