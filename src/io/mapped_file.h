// A file's bytes mapped read-only: the parsers read them in place, with no copy.
#pragma once

#include <filesystem>
#include <string_view>

namespace meander::io {

class MappedFile {
public:
  // Throws IOError("path: cannot open: <reason>"), "path: is a directory", "path: not a
  // regular file" or "path: cannot read: <reason>". An empty file has empty bytes.
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::string_view bytes() const { return {data_, size_}; }

private:
  const char* data_ = "";
  size_t size_ = 0;
};

} // namespace meander::io
