// A picture in memory: what render() makes and write_png() writes.
#pragma once

#include <cstdint>
#include <vector>

namespace meander {

// An 8-bit image, rows top to bottom; rgba holds 4 bytes per pixel.
struct Image {
  int32_t width = 0, height = 0;
  bool has_alpha = false; // written as RGBA if set, else RGB
  std::vector<uint8_t> rgba;
};

} // namespace meander
