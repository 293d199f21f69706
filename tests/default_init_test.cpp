#include "meander/default_init.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <numeric>

namespace meander {
namespace {

constexpr size_t kHugeCount = kHugePageBlock / sizeof(int32_t);

bool huge_page_aligned(const void* p) { return reinterpret_cast<uintptr_t>(p) % size_t(kHugePageAlignment) == 0; }

// A vector that grows from a plain block into a huge-page one and shrinks back: each block
// goes back the way it came (the sanitizer build reports a mismatched delete).
TEST(DefaultInit, BlocksCrossTheHugePageSizeBothWays) {
  UninitVector<int32_t> v(kHugeCount - 1);
  std::iota(v.begin(), v.end(), 0);
  v.push_back(int32_t(kHugeCount - 1));
  v.shrink_to_fit();
  ASSERT_EQ(v.capacity(), kHugeCount);
  EXPECT_TRUE(huge_page_aligned(v.data()));
  EXPECT_EQ(v.back(), int32_t(kHugeCount - 1));
  v.resize(10);
  v.shrink_to_fit();
  EXPECT_EQ(v[9], 9);
}

// A copy of a large array is a huge-page block of its own.
TEST(DefaultInit, LargeCopiesAreHugePageAligned) {
  const UninitVector<std::array<int32_t, 4>> quads(kHugeCount / 4 + 1, {1, 2, 3, 4});
  const UninitVector<std::array<int32_t, 4>> copy = quads;
  EXPECT_TRUE(huge_page_aligned(quads.data()));
  EXPECT_TRUE(huge_page_aligned(copy.data()));
  EXPECT_EQ(copy.back()[3], 4);
}

} // namespace
} // namespace meander
