#include "io/atomic_file.h"
#include "io/formats.h"
#include "meander/error.h"
#include "meander/render.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

#include <string>

namespace meander {

void write_png(const Image& image, const std::filesystem::path& path) {
  if (const std::string extension = io::lowercase_extension(path); extension != ".png")
    throw UsageError(path.string() + ": unknown image format '" + extension + "' (expected .png)");
  if (image.width < 1 || image.height < 1 || image.rgba.size() != size_t(image.width) * image.height * 4)
    throw UsageError(path.string() + ": image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " pixels has " + std::to_string(image.rgba.size()) + " bytes");
  // stb encodes to memory first: its callback is C code, which an IOError thrown from
  // the file must not cross.
  std::vector<unsigned char> rgb;
  const unsigned char* pixels = image.rgba.data();
  if (!image.has_alpha) {
    rgb.reserve(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < image.rgba.size(); i += 4) rgb.insert(rgb.end(), &image.rgba[i], &image.rgba[i] + 3);
    pixels = rgb.data();
  }
  const int channels = image.has_alpha ? 4 : 3;
  std::string png;
  const int ok = stbi_write_png_to_func(
      [](void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<char*>(data), size); },
      &png, image.width, image.height, channels, pixels, image.width * channels);
  if (!ok) throw Error(path.string() + ": PNG encoding failed");
  io::AtomicFile out(path);
  out.bytes(png.data(), png.size());
  out.commit();
}

} // namespace meander
