// The libFuzzer entry point around one target of fuzz_targets.h: a violated invariant
// is printed and aborts, which libFuzzer records as a crash with its input.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>

#define MEANDER_FUZZ_ENTRY(call)                                                                        \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {                            \
    const std::span<const uint8_t> bytes(data, size);                                                   \
    if (const std::string problem = (call); !problem.empty()) {                                         \
      std::fprintf(stderr, "invariant violated: %s\n", problem.c_str());                                \
      std::abort();                                                                                     \
    }                                                                                                   \
    return 0;                                                                                           \
  }
