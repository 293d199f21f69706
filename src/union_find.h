// Disjoint sets over int32 handles: path halving and union by size, so a sequence of
// operations costs near-linear time. Internal to the library.
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace meander {

class UnionFind {
public:
  explicit UnionFind(int32_t n) : parent_(size_t(n)), size_(size_t(n), 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }

  int32_t find(int32_t x) {
    while (parent_[size_t(x)] != x) {
      parent_[size_t(x)] = parent_[size_t(parent_[size_t(x)])];
      x = parent_[size_t(x)];
    }
    return x;
  }

  // Joins the sets of a and b; false if they were already one set.
  bool unite(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[size_t(a)] < size_[size_t(b)]) std::swap(a, b);
    parent_[size_t(b)] = a;
    size_[size_t(a)] += size_[size_t(b)];
    return true;
  }

private:
  std::vector<int32_t> parent_;
  std::vector<int32_t> size_;
};

} // namespace meander
