#include "io/zip.h"

#include "meander/error.h"

#include <array>
#include <cstdint>

namespace meander::io {

namespace {

uint32_t crc32(const std::string& bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void put16(std::string& out, uint32_t v) {
  out.push_back(char(v & 0xFF));
  out.push_back(char((v >> 8) & 0xFF));
}
void put32(std::string& out, uint32_t v) {
  put16(out, v & 0xFFFF);
  put16(out, v >> 16);
}

} // namespace

std::string zip_stored(std::span<const ZipEntry> entries) {
  std::string out, directory;
  for (const ZipEntry& e : entries) {
    if (e.bytes.size() >= UINT32_MAX || out.size() >= UINT32_MAX)
      throw UsageError(e.name + ": too large for a zip archive without Zip64 (4 GiB)");
    const uint32_t crc = crc32(e.bytes), size = uint32_t(e.bytes.size()), offset = uint32_t(out.size());
    // A fixed date (1980-01-01) keeps the archive the same bytes for the same files.
    auto header = [&](std::string& to, bool central) {
      put32(to, central ? 0x02014b50 : 0x04034b50);
      if (central) put16(to, 20); // made by: version 2.0
      put16(to, 20);              // needed to extract: 2.0
      put16(to, 0x0800);          // names are UTF-8
      put16(to, 0);               // stored
      put16(to, 0);               // time
      put16(to, 0x21);            // date
      put32(to, crc);
      put32(to, size);
      put32(to, size);
      put16(to, uint32_t(e.name.size()));
      put16(to, 0); // extra
      if (central) {
        put16(to, 0); // comment
        put16(to, 0); // disk
        put16(to, 0); // internal attributes
        put32(to, 0); // external attributes
        put32(to, offset);
      }
      to += e.name;
    };
    header(out, false);
    out += e.bytes;
    header(directory, true);
  }
  if (out.size() + directory.size() >= UINT32_MAX) throw UsageError("zip archive too large without Zip64 (4 GiB)");
  const uint32_t directory_offset = uint32_t(out.size());
  out += directory;
  put32(out, 0x06054b50);
  put16(out, 0);
  put16(out, 0);
  put16(out, uint32_t(entries.size()));
  put16(out, uint32_t(entries.size()));
  put32(out, uint32_t(directory.size()));
  put32(out, directory_offset);
  put16(out, 0);
  return out;
}

} // namespace meander::io
