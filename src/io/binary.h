// Scalars in a stated byte order at any alignment, for the binary PLY and STL readers
// and writers. memcpy keeps unaligned access defined; compilers turn it and the byte
// reversal into plain loads and bswap.
#pragma once

#include <bit>
#include <cstring>
#include <utility>

namespace meander::io {

inline constexpr bool host_is_little_endian = std::endian::native == std::endian::little;

// The T stored at p, with its bytes reversed when `swap` (file and host byte orders differ).
template <class T> T load(const char* p, bool swap) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template <class T> T load_little_endian(const char* p) { return load<T>(p, !host_is_little_endian); }

template <class T> void store_little_endian(char* p, T value) {
  std::memcpy(p, &value, sizeof(T));
  if constexpr (!host_is_little_endian)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(p[i], p[sizeof(T) - 1 - i]);
}

} // namespace meander::io
