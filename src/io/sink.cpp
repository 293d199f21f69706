#include "io/sink.h"

#include <charconv>
#include <cstring>

namespace meander::io {

namespace {
constexpr size_t buffer_size = size_t(1) << 20;
} // namespace

Sink::Sink() : buffer_(buffer_size) {}

void Sink::real(float value) {
  constexpr size_t longest = 16; // "-1.17549435e-38"
  char* first = room(longest);
  used_ = size_t(std::to_chars(first, first + longest, value).ptr - buffer_.data());
}

void Sink::fixed(double value, int decimals) {
  constexpr size_t longest = 400; // 309 integer digits of the largest double, the sign, decimals
  char* first = room(longest);
  used_ = size_t(std::to_chars(first, first + longest, value, std::chars_format::fixed, decimals).ptr - buffer_.data());
}

void Sink::integer(int64_t value) {
  constexpr size_t longest = 20;
  char* first = room(longest);
  used_ = size_t(std::to_chars(first, first + longest, value).ptr - buffer_.data());
}

void Sink::bytes(const void* data, size_t size) {
  if (size == 0) return; // data may be null then, which memcpy does not allow
  // A block as large as a quarter of the buffer is written as it is: copying it first
  // would cost a pass over it (2.4 GB for a 10M-triangle curve).
  if (buffer_.size() - used_ < size || size >= buffer_.size() / 4) {
    flush();
    if (size >= buffer_.size() / 4) {
      write_at(static_cast<const char*>(data), size, offset_);
      offset_ += size;
      return;
    }
  }
  std::memcpy(buffer_.data() + used_, data, size);
  used_ += size;
}

void Sink::fill(uint64_t size, const Fill& make) {
  flush();
  for (uint64_t done = 0; done < size;) {
    const size_t n = size_t(std::min<uint64_t>(size - done, buffer_.size()));
    make(done, n, buffer_.data());
    write_at(buffer_.data(), n, offset_);
    offset_ += n;
    done += n;
  }
}

void Sink::flush() {
  if (used_ > 0) write_at(buffer_.data(), used_, offset_);
  offset_ += used_;
  used_ = 0;
}

uint64_t Sink::position() { return offset_ + used_; }

void Sink::seek(uint64_t offset) {
  flush();
  offset_ = offset;
}

std::string MemorySink::take() {
  flush();
  return std::move(bytes_);
}

void MemorySink::write_at(const char* data, size_t size, uint64_t offset) {
  if (offset + size > bytes_.size()) bytes_.resize(size_t(offset + size));
  std::memcpy(bytes_.data() + offset, data, size);
}

} // namespace meander::io
