// A file that appears whole or not at all. Bytes go through the sink's buffer into a
// temporary file made with mkstemp in the target's folder (same file system, so the
// final rename is atomic); commit() flushes it to the disk (fsync), renames it over the
// target and flushes the folder, so that after a crash or a power cut the target is the
// new file or the previous one, never a part. If commit() is never reached (an
// exception), the destructor removes the temporary file and a previous target is left
// as it was.
#pragma once

#include "io/sink.h"

#include <filesystem>
#include <span>
#include <string>

namespace meander::io {

class AtomicFile final : public Sink {
public:
  // Throws IOError("path: cannot create file: <reason>") if the folder refuses it.
  explicit AtomicFile(const std::filesystem::path& target);
  ~AtomicFile() override;

  // Writes out the buffer, flushes the file to the disk, renames it over the target and
  // flushes the folder.
  void commit();

  // Commits several files that belong together (an OBJ, its MTL and its textures): all
  // are written out and flushed before the first is renamed, so a full disk leaves none;
  // if a rename still fails, the targets already renamed are removed again.
  static void commit_all(std::span<AtomicFile* const> files);

private:
  void write_at(const char* data, size_t size, uint64_t offset) override;
  // Writes out the buffer, flushes the file to the disk and closes it (once).
  void close();
  void rename();
  [[noreturn]] void fail(std::string_view what, int error) const;

  std::filesystem::path target_;
  std::string temp_;
  int fd_ = -1;
  bool committed_ = false;
};

} // namespace meander::io
