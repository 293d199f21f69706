#include "page_sizes.h"

#include <gtest/gtest.h>

namespace meander {
namespace {

constexpr uintptr_t kMiB = uintptr_t(1) << 20;
constexpr uintptr_t kBegin = 256 * kMiB + 4096; // page-aligned, 4 KiB past a huge page
constexpr uintptr_t kEnd = kBegin + 64 * kMiB;

TEST(PageSizes, FirstBlockTriesHugePagesFromItsFirstHugePageBoundaryAndSmallOnesAfter) {
  PageSizes sizes;
  EXPECT_EQ(sizes.split(kBegin, kEnd), 258 * kMiB + PageSizes::kSample);
  // A block too small for the sample is all on huge pages.
  EXPECT_EQ(sizes.split(kBegin, kBegin + 4 * kMiB), kBegin + 4 * kMiB);
}

TEST(PageSizes, HugePagesAreTriedUntilAWholeSampleWasMeasured) {
  PageSizes sizes;
  sizes.record(PageSizes::huge, 2 * kMiB, 0.001);
  EXPECT_EQ(sizes.split(kBegin, kEnd), 258 * kMiB + PageSizes::kSample);
  sizes.record(PageSizes::huge, PageSizes::kSample, 0.01);
  EXPECT_EQ(sizes.split(kBegin, kEnd), kBegin) << "small pages untried: the whole block tries them";
}

TEST(PageSizes, EachBlockTakesTheSizeThatCostLessPerByte) {
  // As measured on an Intel host: fresh huge pages 2.4 ms/MiB, small ones 0.33 ms/MiB.
  PageSizes intel;
  intel.record(PageSizes::huge, 8 * kMiB, 8 * 2.4e-3);
  intel.record(PageSizes::small, 56 * kMiB, 56 * 0.33e-3);
  EXPECT_EQ(intel.split(kBegin, kEnd), kBegin);
  // Small pages that a host charges for at their first use by the program.
  PageSizes amd;
  amd.record(PageSizes::huge, 8 * kMiB, 8 * 0.1e-3);
  amd.record(PageSizes::small, 56 * kMiB, 56 * 2.0e-3);
  EXPECT_EQ(amd.split(kBegin, kEnd), kEnd);
}

TEST(PageSizes, AChoiceALuckyStartMadeIsTakenBack) {
  PageSizes sizes;
  sizes.record(PageSizes::huge, 8 * kMiB, 8 * 0.05e-3); // pages the host still backed
  sizes.record(PageSizes::small, 56 * kMiB, 56 * 0.33e-3);
  ASSERT_EQ(sizes.split(kBegin, kEnd), kEnd);
  sizes.record(PageSizes::huge, 2 * kMiB, 2 * 1.0e-3); // a quarter of a sample: 0.29 ms/MiB
  EXPECT_EQ(sizes.split(kBegin, kEnd), kEnd) << "a small measurement weighs in proportion";
  sizes.record(PageSizes::huge, 64 * kMiB, 64 * 2.4e-3); // the next block's, fresh
  EXPECT_EQ(sizes.split(kBegin, kEnd), kBegin);
}

} // namespace
} // namespace meander
