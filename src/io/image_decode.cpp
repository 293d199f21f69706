#include "io/image_codec.h"
#include "io/reader_support.h"

#include <climits>

// Only memory is decoded: files are read (and their errors reported) by Meander.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>

namespace meander::io {

Texture decode_image(std::string_view bytes, std::string_view name) {
  constexpr int max_side = 16384;
  if (bytes.size() > size_t(INT_MAX)) fail_input(name, "cannot decode image: file too large");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = int(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &width, &height, &channels))
    fail_input(name, std::string("cannot decode image: ") + stbi_failure_reason());
  if (width > max_side || height > max_side)
    fail_input(name, "cannot decode image: " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels (at most " + std::to_string(max_side) + " on a side)");
  stbi_uc* pixels = stbi_load_from_memory(data, size, &width, &height, &channels, 4);
  if (!pixels) fail_input(name, std::string("cannot decode image: ") + stbi_failure_reason());
  Texture texture{.width = width, .height = height};
  texture.rgba.assign(pixels, pixels + size_t(width) * size_t(height) * 4);
  stbi_image_free(pixels);
  return texture;
}

} // namespace meander::io
