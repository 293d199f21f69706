// What the OBJ readers share: vertex lines and the 1-based, negative or forward indices
// that faces and lines use for vertices and texture coordinates.
#pragma once

#include "io/reader_support.h"
#include "io/text_cursor.h"

#include <string>
#include <string_view>
#include <vector>

namespace meander::io {

// "face references vertex 9001 but only 8000 exist".
inline std::string missing_element(std::string_view element, std::string_view target, int64_t index, int64_t count) {
  return std::string(element) + " references " + std::string(target) + " " + std::to_string(index) + " but only " +
         std::to_string(count) + " exist";
}

inline void read_position(TextCursor& in, std::vector<Vec3>& positions) {
  if (int64_t(positions.size()) == max_count) in.fail(too_many(uint64_t(max_count) + 1, "vertices"));
  positions.push_back(read_point(in));
}

// A positive index may point forward, to a vertex defined further down, so positive
// indices are checked once at the end against the final count: the largest one and its
// line are enough to report the problem. One per kind of target (vertex, texture
// coordinate).
struct ForwardIndices {
  std::string_view target; // "vertex" or "texture coordinate"
  int64_t largest = 0, line = 0;

  // The 0-based index of OBJ index `index` read on the cursor's line, where `count`
  // targets are defined so far; `element` is "face" or "line".
  int32_t resolve(const TextCursor& in, int64_t index, std::string_view element, int64_t count) {
    if (index > 0) {
      if (index > largest) largest = index, line = in.line();
      return int32_t(index - 1);
    }
    if (index < 0 && index >= -count) return int32_t(count + index);
    in.fail(index == 0 ? std::string(target) + " index 0 is invalid (OBJ indices start at 1)"
                       : missing_element(element, target, index, count));
  }
  void check(std::string_view name, std::string_view element, int64_t count) const {
    if (largest > count) fail_at_line(name, line, missing_element(element, target, largest, count));
  }
};

} // namespace meander::io
