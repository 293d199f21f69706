// A zip archive in memory, its entries stored (not compressed): what the studio offers
// for results that are several files (OBJ + MTL + PNG). Written by libzip.
#pragma once

#include <span>
#include <string>

namespace meander::io {

struct ZipEntry {
  std::string name; // path inside the archive, '/' separated
  std::string bytes;
};

// The archive (Zip64 where an entry or the whole passes 4 GiB), the same bytes for the
// same entries. Throws IOError if libzip fails.
std::string zip_stored(std::span<const ZipEntry> entries);

} // namespace meander::io
