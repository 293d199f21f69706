// Disjoint sets over int32 handles: path halving and union by size, so a sequence of
// operations costs near-linear time; and a variant whose elements carry a parity.
// Internal to the library.
#pragma once

#include <atomic>
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

  // unite() for many threads at once: the root of larger index is linked under the
  // other by a compare-and-swap, so every parent has a smaller index than its child (no
  // cycle can form) and no lock is needed. Such sets keep no size, which only keeps
  // unite()'s trees low; after the threads join, every other member works as usual.
  bool unite_concurrently(int32_t a, int32_t b) {
    for (;;) {
      a = find_concurrently(a);
      b = find_concurrently(b);
      if (a == b) return false;
      if (a < b) std::swap(a, b);
      int32_t root = entry(a).load(std::memory_order_relaxed);
      if (root < 0 && entry(a).compare_exchange_strong(root, b, std::memory_order_relaxed)) return true;
    }
  }

  // x stands for its set (find(x) == x), without the cost of a find.
  bool is_root(int32_t x) const { return parent_[size_t(x)] < 0; }

private:
  std::atomic_ref<int32_t> entry(int32_t x) { return std::atomic_ref<int32_t>(parent_[size_t(x)]); }

  // find() with path halving where other threads may be linking: a parent only ever
  // moves up towards its root, so a halving that reads a stale grandparent is harmless.
  int32_t find_concurrently(int32_t x) {
    for (int32_t p; (p = entry(x).load(std::memory_order_relaxed)) >= 0;) {
      const int32_t grandparent = entry(p).load(std::memory_order_relaxed);
      if (grandparent < 0) return p;
      entry(x).store(grandparent, std::memory_order_relaxed);
      x = grandparent;
    }
    return x;
  }

  // One array, so a find touches half the memory of separate parent and size arrays:
  // parent_[x] is x's parent, or minus the size of x's set when x is a root (some
  // negative number after unite_concurrently).
  std::vector<int32_t> parent_;
};

// Union-find whose elements carry a parity relative to their root (path halving, union
// by size, as UnionFind): for find_sheets (mesh_scan.h), whether a face is wound against
// the root of its sheet.
class ParityUnionFind {
public:
  explicit ParityUnionFind(int32_t n) : parent_(size_t(n), -1), parity_(size_t(n), 0) {}

  // The root of x, and x's parity relative to it.
  std::pair<int32_t, uint8_t> find(int32_t x) {
    uint8_t parity = 0;
    for (int32_t p; (p = parent_[size_t(x)]) >= 0;) {
      const int32_t grandparent = parent_[size_t(p)];
      if (grandparent < 0) return {p, uint8_t(parity ^ parity_[size_t(x)])};
      parity_[size_t(x)] ^= parity_[size_t(p)]; // x hangs from its grandparent now
      parent_[size_t(x)] = grandparent;
      parity ^= parity_[size_t(x)];
      x = grandparent;
    }
    return {x, parity};
  }

  // Records that a and b differ in parity iff `odd`; false if that contradicts what was
  // recorded before.
  bool unite(int32_t a, int32_t b, uint8_t odd) {
    auto [ra, pa] = find(a);
    auto [rb, pb] = find(b);
    if (ra == rb) return (pa ^ pb) == odd;
    if (parent_[size_t(ra)] > parent_[size_t(rb)]) std::swap(ra, rb); // ra's set is the larger
    parent_[size_t(ra)] += parent_[size_t(rb)];
    parent_[size_t(rb)] = ra;
    parity_[size_t(rb)] = pa ^ pb ^ odd;
    return true;
  }

private:
  std::vector<int32_t> parent_; // as in UnionFind: minus the set's size at a root
  std::vector<uint8_t> parity_; // relative to the parent
};

} // namespace meander
