// A small, fast generator whose sequence is the same on every platform and standard
// library (std::uniform_int_distribution is not), so `--seed N` reproduces byte-identical
// output everywhere. Internal to the library.
#pragma once

#include <cstdint>

namespace meander {

class Random {
public:
  explicit Random(uint64_t seed) : state_(seed) {}

  // splitmix64
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  // Uniform in [0, n) by Lemire's multiply-shift (bias below 2^-32 for n < 2^32, which
  // does not matter for picking trees).
  uint32_t below(uint32_t n) { return uint32_t((uint64_t(uint32_t(next() >> 32)) * n) >> 32); }

  // Uniform in [0, 1) from the top 53 bits.
  double unit() { return double(next() >> 11) * 0x1p-53; }

private:
  uint64_t state_;
};

} // namespace meander
