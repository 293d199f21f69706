#include "io/image_codec.h"
#include "io/reader_support.h"

#include <turbojpeg.h>

#include <cctype>
#include <climits>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

// Only memory is decoded: files are read (and their errors reported) by Meander.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
#define STBI_NO_JPEG
#include <stb/stb_image.h>

namespace meander::io {
namespace {

constexpr int max_side = 16384;

// A texture has at least one pixel (a BMP may declare a height of 0, found by fuzz_image).
void check_size(int width, int height, std::string_view name, int64_t max_pixels) {
  if (width < 1 || height < 1 || width > max_side || height > max_side)
    fail_input(name, "cannot decode image: " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels (1 to " + std::to_string(max_side) + " on a side)");
  if (max_pixels > 0 && int64_t(width) * height > max_pixels)
    fail_input(name, std::to_string(width) + "x" + std::to_string(height) + " pixels, more than the " +
                         std::to_string(max_pixels) + " allowed");
}

// JPEG through libjpeg-turbo: Debian 12's stb_image (a 2022-09 snapshot) reads and writes
// past its Huffman tables on crafted files (nothings/stb#1289 and #1291, fixed upstream
// later), as fuzz_image found within seconds. A warning (a truncated file) still gives
// the picture, as image viewers show it.
Texture decode_jpeg(std::string_view bytes, std::string_view name, int64_t max_pixels) {
  const std::unique_ptr<void, int (*)(tjhandle)> decoder(tjInitDecompress(), tjDestroy);
  if (!decoder) fail_input(name, "cannot decode image: cannot start the JPEG decoder");
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const auto failed = [&] { return std::string("cannot decode image: ") + tjGetErrorStr2(decoder.get()); };
  int width = 0, height = 0, subsampling = 0, colorspace = 0;
  if (tjDecompressHeader3(decoder.get(), data, static_cast<unsigned long>(bytes.size()), &width, &height, &subsampling,
                          &colorspace) != 0)
    fail_input(name, failed());
  check_size(width, height, name, max_pixels);
  Texture texture{.width = width, .height = height};
  texture.rgba.resize(size_t(width) * size_t(height) * 4);
  if (tjDecompress2(decoder.get(), data, static_cast<unsigned long>(bytes.size()), texture.rgba.data(), width, 0, height,
                    TJPF_RGBA, 0) != 0 &&
      tjGetErrorCode(decoder.get()) != TJERR_WARNING)
    fail_input(name, failed());
  return texture;
}

// The PNG as stb_image should see it, or nothing if a chunk is longer than the bytes
// after its header, the last one included: stb trusts an IDAT's length and allocates it
// before reading (1.7 GB for a 100-byte file, 1 GB for a 43-byte one), and copies an empty first IDAT from a null buffer (undefined
// behaviour), both found by fuzz_image; empty IDAT chunks hold nothing and are left out.
// The walk stops at IEND; what follows it is ignored, as by stb.
std::optional<std::string> png_for_stb(std::string_view bytes) {
  const auto be32 = [&](size_t at) {
    uint32_t v = 0;
    for (size_t k = 0; k < 4; ++k) v = v << 8 | uint8_t(bytes[at + k]);
    return v;
  };
  std::string kept(bytes.substr(0, 8));
  size_t at = 8;
  while (at + 8 <= bytes.size()) {
    const uint64_t length = be32(at);
    if (length + 12 > bytes.size() - at) return std::nullopt; // the last one cut short too
    const std::string_view type = bytes.substr(at + 4, 4);
    if (length > 0 || type != "IDAT") kept += bytes.substr(at, 12 + length);
    at += 12 + length;
    if (type == "IEND") return kept;
  }
  return kept += bytes.substr(at); // less than a chunk's header: stb says the file is cut
}

// Why stb_image must not be given a PNM (P5, P6), or "": a header number of more than 9
// digits, which it reads into an int without a bound (a signed overflow), or 16-bit
// samples (a largest value over 255), which it converts past the end of its buffer; both
// found by fuzz_image.
std::string pnm_refusal(std::string_view bytes) {
  size_t at = 2;
  uint64_t number = 0;
  for (int numbers = 0; numbers < 3 && at < bytes.size();) {
    if (bytes[at] == '#') {
      while (at < bytes.size() && bytes[at] != '\n' && bytes[at] != '\r') ++at;
    } else if (std::isspace(static_cast<unsigned char>(bytes[at]))) {
      ++at;
    } else {
      size_t digits = 0;
      for (number = 0; at < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[at])); ++at, ++digits)
        if (digits < 10) number = number * 10 + uint64_t(bytes[at] - '0');
      if (digits == 0) return ""; // not a number: stb refuses the header
      if (digits > 9) return "a number of the PNM header has more than 9 digits";
      if (++numbers == 3 && number > 255) return "16-bit PNM samples are not supported";
    }
  }
  return "";
}

// Whether the pixels the header of an uncompressed image claims fit in its bytes, and
// those of a run-length TGA in 128 pixels a byte: stb_image allocates the whole picture
// before reading it (1.6 GB for a 32-byte TGA claiming 15360 x 15360 pixels, found by
// fuzz_image). Compressed formats (PNG, GIF, PSD, HDR, PIC) are bounded by max_side.
bool claimed_pixels_fit(std::string_view bytes, int width, int height) {
  const uint64_t pixels = uint64_t(width) * uint64_t(height), size = bytes.size();
  if (bytes.starts_with("BM")) return pixels <= 8 * size; // 1 bit a pixel at the least
  if (bytes.starts_with("P5") || bytes.starts_with("P6")) return pixels <= size;
  for (std::string_view magic : {"\x89PNG", "GIF8", "8BPS", "\x53\x80\xF6\x34", "#?"})
    if (bytes.starts_with(magic)) return true;
  // A TGA (no magic): its image type is byte 2.
  switch (bytes.size() > 2 ? uint8_t(bytes[2]) : 0) {
  case 1: case 2: case 3: return pixels <= size;
  case 9: case 10: case 11: return pixels <= 128 * size;
  default: return true;
  }
}

} // namespace

Texture decode_image(std::string_view bytes, std::string_view name, int64_t max_pixels) {
  if (bytes.size() > size_t(INT_MAX)) fail_input(name, "cannot decode image: file too large");
  if (bytes.starts_with("\xFF\xD8")) return decode_jpeg(bytes, name, max_pixels);
  std::string png;
  if (bytes.starts_with("\x89PNG\r\n\x1A\n")) {
    std::optional<std::string> chunks = png_for_stb(bytes);
    if (!chunks) fail_input(name, "cannot decode image: a PNG chunk is longer than the file");
    png = std::move(*chunks);
    bytes = png;
  }
  if (bytes.starts_with("P5") || bytes.starts_with("P6"))
    if (const std::string refusal = pnm_refusal(bytes); !refusal.empty()) fail_input(name, "cannot decode image: " + refusal);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = int(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &width, &height, &channels))
    fail_input(name, std::string("cannot decode image: ") + stbi_failure_reason());
  check_size(width, height, name, max_pixels);
  if (!claimed_pixels_fit(bytes, width, height))
    fail_input(name, "cannot decode image: " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels claimed by a file of " + std::to_string(bytes.size()) + " bytes");
  stbi_uc* pixels = stbi_load_from_memory(data, size, &width, &height, &channels, 4);
  if (!pixels) fail_input(name, std::string("cannot decode image: ") + stbi_failure_reason());
  Texture texture{.width = width, .height = height};
  texture.rgba.assign(pixels, pixels + size_t(width) * size_t(height) * 4);
  stbi_image_free(pixels);
  return texture;
}

} // namespace meander::io
