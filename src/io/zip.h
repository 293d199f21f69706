// A zip archive in memory, its entries stored (not compressed): what the studio offers
// for results that are several files (OBJ + MTL + PNG). Every zip reader opens it.
#pragma once

#include <span>
#include <string>

namespace meander::io {

struct ZipEntry {
  std::string name; // path inside the archive, '/' separated
  std::string bytes;
};

// The archive. Throws UsageError if an entry or the whole exceeds 4 GiB (no Zip64).
std::string zip_stored(std::span<const ZipEntry> entries);

} // namespace meander::io
