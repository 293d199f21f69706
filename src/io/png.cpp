#include "io/formats.h"
#include "io/image_codec.h"
#include "meander/error.h"
#include "meander/io.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

#include <string>

namespace meander {

namespace io {

std::string encode_png(const uint8_t* pixels, int32_t width, int32_t height, int channels, std::string_view name) {
  // stb encodes to memory: its callback is C code, which an exception must not cross.
  std::string png;
  const int ok = stbi_write_png_to_func(
      [](void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<char*>(data), size); },
      &png, width, height, channels, pixels, width * channels);
  if (!ok) throw Error(std::string(name) + ": PNG encoding failed");
  return png;
}

} // namespace io

void require_png_path(const std::filesystem::path& path) {
  if (const std::string extension = io::lowercase_extension(path); extension != ".png")
    throw UsageError(path.string() + ": unknown image format '" + extension + "' (expected .png)");
}

void write_png(const Image& image, const std::filesystem::path& path) {
  require_png_path(path);
  if (image.width < 1 || image.height < 1 || image.rgba.size() != size_t(image.width) * image.height * 4)
    throw UsageError(path.string() + ": image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " pixels has " + std::to_string(image.rgba.size()) + " bytes");
  std::vector<unsigned char> rgb;
  const unsigned char* pixels = image.rgba.data();
  if (!image.has_alpha) {
    rgb.reserve(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < image.rgba.size(); i += 4) rgb.insert(rgb.end(), &image.rgba[i], &image.rgba[i] + 3);
    pixels = rgb.data();
  }
  const std::string png = io::encode_png(pixels, image.width, image.height, image.has_alpha ? 4 : 3, path.string());
  write_bytes(path, png);
}

} // namespace meander
