// Merging the corners of a triangle soup (STL, glTF primitives) into shared vertices.
#pragma once

#include "io/reader_support.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <string_view>
#include <vector>

namespace meander::io {

// Merges the corners of a triangle soup into shared vertices. Positions that compare
// equal as floats are one vertex (so -0 and +0 are one), numbered in order of first
// appearance; an open-addressing table of vertex indices keeps it linear.
class Welder {
public:
  Welder(std::vector<Vec3>& positions, size_t expected_vertices, std::string_view name)
      : positions_(positions), name_(name) {
    rebuild(std::bit_ceil(std::max<size_t>(16, 2 * expected_vertices)));
  }

  int32_t add(Vec3 p) {
    const Key key = key_of(p);
    size_t slot = hash(key) & mask_;
    for (; slots_[slot] >= 0; slot = (slot + 1) & mask_)
      if (key_of(positions_[size_t(slots_[slot])]) == key) return slots_[slot];
    if (int64_t(positions_.size()) == max_count) fail_input(name_, too_many(uint64_t(max_count) + 1, "vertices"));
    const int32_t index = int32_t(positions_.size());
    positions_.push_back(p);
    slots_[slot] = index;
    // At most half full, so probe runs stay short.
    if (2 * positions_.size() > slots_.size()) rebuild(2 * slots_.size());
    return index;
  }

private:
  using Key = std::array<uint32_t, 3>;
  // Adding +0 turns -0 into +0 and leaves every other value as it is.
  static Key key_of(Vec3 p) {
    return {std::bit_cast<uint32_t>(p.x + 0.0f), std::bit_cast<uint32_t>(p.y + 0.0f),
            std::bit_cast<uint32_t>(p.z + 0.0f)};
  }
  static size_t hash(const Key& k) {
    uint64_t h = k[0] * 0x9E3779B97F4A7C15ull ^ k[1] * 0xC2B2AE3D27D4EB4Full ^ k[2] * 0x165667B19E3779F9ull;
    h ^= h >> 32;
    h *= 0xD6E8FEB86659FD93ull;
    return size_t(h ^ (h >> 32));
  }
  void rebuild(size_t size) {
    slots_.assign(size, -1);
    mask_ = size - 1;
    for (size_t i = 0; i < positions_.size(); ++i) {
      size_t slot = hash(key_of(positions_[i])) & mask_;
      while (slots_[slot] >= 0) slot = (slot + 1) & mask_;
      slots_[slot] = int32_t(i);
    }
  }

  std::vector<Vec3>& positions_;
  std::string_view name_;
  std::vector<int32_t> slots_;
  size_t mask_ = 0;
};

} // namespace meander::io
