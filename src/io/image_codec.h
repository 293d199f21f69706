// Image files as the texture readers and writers need them: any format stb_image
// decodes (PNG, JPEG, BMP, TGA, ...) into RGBA8, and PNG encoding to bytes in memory,
// so that a writer can put them into a GLB or an atomic file.
#pragma once

#include "meander/textured_mesh.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace meander::io {

// Throws InputError("name: cannot decode image: <reason>") for bytes that are not an
// image stb_image reads, and for images wider or taller than 16384 pixels (checked
// before the pixels are allocated), as for images of more than `max_pixels` pixels when
// it is not 0. Grey and RGB images get opaque RGBA.
Texture decode_image(std::string_view bytes, std::string_view name, int64_t max_pixels = 0);

// The pixels (rows top to bottom, `channels` bytes each: 3 RGB or 4 RGBA) as PNG bytes.
// Throws Error("name: PNG encoding failed") if stb refuses them.
std::string encode_png(const uint8_t* pixels, int32_t width, int32_t height, int channels, std::string_view name);

} // namespace meander::io
