// Writers never leave a partial file (io.h, src/io/atomic_file): the CLI killed in the
// middle of writing a large output, when no cleanup code can run, leaves at the target
// either no file or the previous complete one. Only its temporary file (".NAME.tmp.XXXXXX"
// beside the target) is left behind, under a name no reader takes for the output. The
// kill is the kernel's, at a file-size limit (RLIMIT_FSIZE, SIGXFSZ), so that where the
// program is when it dies does not depend on timing.
#include "test_support.h"

#include "meander/io.h"

#include <gtest/gtest.h>

#include <csignal>

namespace meander {
namespace {

namespace fs = std::filesystem;

constexpr uint64_t mebibyte = uint64_t(1) << 20;

// Runs `meander generate sphere` of about a million faces (an OBJ of ~40 MB) into
// `target` with files limited to a megabyte: the kernel ends it while it writes.
void kill_while_writing(const fs::path& target) {
  const test::CommandResult r =
      test::run_cli({"generate", "sphere", "--faces", "1000000", "-o", target.string()}, mebibyte);
  ASSERT_EQ(r.exit_code, 128 + SIGXFSZ) << r.err;
}

TEST(AtomicFile, KilledMidWriteLeavesNoFile) {
  const fs::path target = test::output_dir() / "big.obj";
  kill_while_writing(target);
  EXPECT_FALSE(fs::exists(target));
}

TEST(AtomicFile, KilledMidWriteLeavesThePreviousFileWhole) {
  const fs::path target = test::output_dir() / "big.obj";
  ASSERT_EQ(test::run_cli({"generate", "sphere", "--faces", "100", "-o", target.string()}).exit_code, 0);
  const std::string previous = test::read_file(target);
  ASSERT_FALSE(previous.empty());
  kill_while_writing(target);
  EXPECT_EQ(test::read_file(target), previous);
}

// A target written again is the new file once the writer returns, and nothing else is
// left in its folder.
TEST(AtomicFile, TargetIsReplacedAndNothingLeftBeside) {
  const fs::path dir = test::output_dir();
  const fs::path target = dir / "curve.ply";
  for (const float x : {1.0f, 2.0f}) {
    Polylines curve;
    curve.points.assign(1000, Vec3{x, 0, 0});
    curve.start = {0, int32_t(curve.points.size())};
    write_polylines(curve, target);
    const Polylines read = read_polylines(target);
    ASSERT_EQ(read.points.size(), curve.points.size());
    EXPECT_EQ(read.points.front().x, x);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  }
}

// A curve's points and edges are made a buffer at a time (Sink::fill). The header is 186
// bytes (8-digit counts), so every float of the points lies 2 bytes off a multiple of 4,
// and records are cut at every buffer's end: read back, it is still the curve.
TEST(AtomicFile, LargeCurveReadsBackExactly) {
  const fs::path target = test::output_dir() / "curve.ply";
  Polylines curve;
  for (int32_t i = 0; i < 10'000'000; ++i) curve.points.push_back({float(i), float(i % 7), -float(i)});
  curve.start = {0, 3'000'001, 7'654'321, int32_t(curve.points.size())};
  write_polylines(curve, target);
  const Polylines read = read_polylines(target);
  EXPECT_EQ(read.start, curve.start);
  EXPECT_TRUE(read.points == curve.points);
}

} // namespace
} // namespace meander
