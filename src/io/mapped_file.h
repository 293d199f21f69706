// A file's bytes mapped read-only: the parsers read them in place, with no copy.
#pragma once

#include <atomic>
#include <filesystem>
#include <string_view>
#include <thread>

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
  // Brings a large file's pages in ahead of the parser, front to back (see the .cpp).
  std::thread reader_;
  std::atomic<bool> stop_reading_{false};
};

} // namespace meander::io
