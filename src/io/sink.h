// Where a writer's bytes go: a file that appears whole or not at all (AtomicFile,
// atomic_file.h) or memory (MemorySink). Every writer formats into the sink's buffer
// through the same calls, so a format is written once for both.
#pragma once

#include "io/binary.h"

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace meander::io {

class Sink {
public:
  virtual ~Sink() = default;
  Sink(const Sink&) = delete;
  Sink& operator=(const Sink&) = delete;

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

  // Writes `size` bytes from the current position: make(offset, n, dst) puts the n bytes
  // that start `offset` bytes into them at dst, asked for pieces in order, of any size and
  // at any alignment. For a region a caller makes in parallel pieces (a curve's points).
  using Fill = std::function<void(uint64_t offset, size_t size, char* dst)>;
  void fill(uint64_t size, const Fill& make);

  // The offset of the next byte, and a move to another (past the end leaves a hole that
  // a later seek back fills): for formats whose sections are written out of order.
  uint64_t position();
  void seek(uint64_t offset);

protected:
  Sink();
  // Writes out what the buffer holds.
  void flush();
  // Puts `size` bytes at `offset`; throws IOError when it cannot.
  virtual void write_at(const char* data, size_t size, uint64_t offset) = 0;

private:
  // At least n (<= the buffer's size) free bytes at the end of the buffer.
  char* room(size_t n) {
    if (buffer_.size() - used_ < n) flush();
    return buffer_.data() + used_;
  }

  std::vector<char> buffer_;
  size_t used_ = 0;
  uint64_t offset_ = 0; // where the buffer's first byte goes
};

// The bytes in a string, for a caller that sends them on (the studio's downloads).
class MemorySink final : public Sink {
public:
  // The bytes written; the sink is empty afterwards.
  std::string take();

private:
  void write_at(const char* data, size_t size, uint64_t offset) override;
  std::string bytes_;
};

} // namespace meander::io
