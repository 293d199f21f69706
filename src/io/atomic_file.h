// A file that appears whole or not at all. Bytes go through a large buffer into a
// temporary file made with mkstemp in the target's folder (same file system, so the
// final rename is atomic); commit() renames it over the target. If commit() is never
// reached (an exception), the destructor removes the temporary file and a pre-existing
// target is left untouched.
//
// The file's blocks are reserved ahead of the writes (fallocate, in steps that double up
// to 64 MiB, or at once to the size expect_size gives) and the file cut back to what was
// written when it closes: with delayed allocation each buffered write reserves its
// blocks page by page and writeback then allocates them, several times slower for a
// curve of gigabytes (docs/robustness.md, "Atomic outputs"). Where the file system
// cannot reserve (or is full), the writes go on without.
//
// A large file is also written behind: every 16 MiB of consecutive bytes are sent to the
// disk at once, and once 128 MiB more have followed they are dropped from the page cache,
// as far as they have reached the disk by then (what has not stays cached, as any
// write's bytes would). This is what Linux 6.14's RWF_DONTCACHE does, by hand so that any
// kernel has it. A large curve otherwise takes as much page cache as it has bytes, which
// the kernel must find free pages for, dearly on a VM whose host takes back the memory
// the guest frees (docs/robustness.md, "Atomic outputs"). The page cache of the written
// bytes is then reused over and over.
//
// A large region whose bytes the caller can make in any order of pieces (fill(): a
// curve's points and edges) skips the page cache altogether: its whole pages are made in
// place in a few page-aligned buffers and written with O_DIRECT by a thread of the file's
// own while the caller makes the next ones; only the partial pages at its ends go through
// the page cache. Written through the page cache during the spanning forest, a curve's
// edges slow the forest down (the copy into it, finding it free pages and writing them
// back; docs/robustness.md, "Atomic outputs"). The caller waits for a free buffer, so a
// disk slower than the caller sets the pace, as it would through the page cache; where
// the file system refuses O_DIRECT everything goes through the page cache.
#pragma once

#include "io/binary.h"

#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace meander::io {

class AtomicFile {
public:
  // Throws IOError("path: cannot create file: <reason>") if the folder refuses it.
  explicit AtomicFile(const std::filesystem::path& target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void text(std::string_view s) { bytes(s.data(), s.size()); }
  void put(char c) {
    *room(1) = c;
    ++used_;
  }
  // The shortest decimal that reads back as the same float (std::to_chars).
  void real(float value);
  // A fixed number of decimals, for coordinates where a pixel fraction is enough (SVG).
  void fixed(double value, int decimals);
  void integer(int64_t value);
  void bytes(const void* data, size_t size);
  template <class T> void little_endian(T value) {
    store_little_endian(room(sizeof(T)), value);
    used_ += sizeof(T);
  }

  // The file will be `size` bytes long: its blocks are reserved at once, and never past
  // that, so that closing it cuts nothing back: on an ext4 mounted with `discard`,
  // cutting back the last step's unused blocks waits for the journal, behind the discards
  // of a file just deleted (docs/robustness.md, "Atomic outputs").
  void expect_size(uint64_t size);

  // Writes `size` bytes from the current position: make(offset, n, dst) puts the n bytes
  // that start `offset` bytes into them at dst, asked for pieces in order, of any size and
  // at any alignment. Large regions are written direct, as the header says.
  using Fill = std::function<void(uint64_t offset, size_t size, char* dst)>;
  void fill(uint64_t size, const Fill& make);

  // The offset of the next byte, and a move to another (past the end leaves a hole that
  // a later seek back fills): for formats whose sections are written out of order.
  uint64_t position();
  void seek(uint64_t offset);

  // Writes out the buffer, closes the file and renames it over the target.
  void commit();

  // Commits several files that belong together (an OBJ, its MTL and its textures): all
  // are written out and closed before the first is renamed, so a full disk leaves none;
  // if a rename still fails, the targets already renamed are removed again.
  static void commit_all(std::span<AtomicFile* const> files);

private:
  // At least n (<= the buffer's size) free bytes at the end of the buffer.
  char* room(size_t n) {
    if (buffer_.size() - used_ < n) flush();
    return buffer_.data() + used_;
  }
  void flush();
  // Writes out the buffer and closes the file (once).
  void close();
  void write_all(const char* data, size_t size);
  // Bytes through the page cache at `at`, once no direct write still to come covers them.
  void write_cached(const char* data, size_t size, uint64_t at);
  // Reserves the file's blocks up to at least `end` while the file system can.
  void reserve(uint64_t end);
  // Sends bytes [begin, end), just written, to the disk and drops earlier ones from the
  // page cache, as the header says.
  void write_behind(uint64_t begin, uint64_t end);
  [[noreturn]] void fail(std::string_view what, int error) const;

  std::filesystem::path target_;
  std::string temp_;
  int fd_ = -1;
  bool committed_ = false;
  std::vector<char> buffer_;
  size_t used_ = 0;
  uint64_t offset_ = 0;   // where the next write() goes
  uint64_t written_ = 0;  // the end of the furthest byte written: the file's size
  uint64_t reserved_ = 0; // the file's size as fallocate left it
  uint64_t expected_ = UINT64_MAX; // what expect_size said: reserve no further
  bool reserving_ = true;
  // Consecutive bytes written but not yet sent to the disk, and the ranges sent whose
  // pages are still cached.
  uint64_t unsent_begin_ = 0, unsent_end_ = 0;
  std::deque<std::pair<uint64_t, uint64_t>> sent_;
  bool writing_behind_ = true;
  struct Direct;
  std::unique_ptr<Direct> direct_; // the O_DIRECT writer, from the first large fill()
  bool direct_tried_ = false;
};

} // namespace meander::io
