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

namespace {

// The PNG's bytes; `name` stands for the file in messages.
std::string png_bytes(const Image& image, const std::string& name) {
  if (image.width < 1 || image.height < 1 || image.rgba.size() != size_t(image.width) * image.height * 4)
    throw UsageError(name + ": image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " pixels has " + std::to_string(image.rgba.size()) + " bytes");
  std::vector<unsigned char> rgb;
  const unsigned char* pixels = image.rgba.data();
  if (!image.has_alpha) {
    rgb.reserve(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < image.rgba.size(); i += 4) rgb.insert(rgb.end(), &image.rgba[i], &image.rgba[i] + 3);
    pixels = rgb.data();
  }
  return io::encode_png(pixels, image.width, image.height, image.has_alpha ? 4 : 3, name);
}

} // namespace

void write_png(const Image& image, const std::filesystem::path& path) {
  require_png_path(path);
  write_bytes(path, png_bytes(image, path.string()));
}

std::string png_file_bytes(const Image& image) { return png_bytes(image, "PNG image"); }

} // namespace meander
