// Shared by the io tests: binary inputs built byte by byte (PLY bodies, STL files), and
// the message of an expected exception.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

namespace meander::test {

static_assert(std::endian::native == std::endian::little, "the byte builders assume a little-endian host");

template <class T> std::string little(T value) {
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}

template <class T> std::string big(T value) {
  std::string bytes = little(value);
  std::reverse(bytes.begin(), bytes.end());
  return bytes;
}

inline std::string little_floats(std::initializer_list<float> values) {
  std::string bytes;
  for (float v : values) bytes += little(v);
  return bytes;
}

// 80 header bytes (`header` padded with spaces), the triangle count, then one 50-byte
// record per triangle: a zero normal and its nine coordinates.
inline std::string binary_stl(std::string header, uint32_t count, const std::vector<std::array<float, 9>>& triangles) {
  header.resize(80, ' ');
  std::string bytes = header + little(count);
  for (const auto& t : triangles) {
    bytes += little_floats({0, 0, 0});
    for (float v : t) bytes += little(v);
    bytes += little(uint16_t(0));
  }
  return bytes;
}

// The what() of the E that f throws; a test failure if it throws nothing (another
// exception type escapes and fails the test too).
template <class E, class F> std::string message_of(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception";
  return {};
}

} // namespace meander::test
