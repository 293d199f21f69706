// Writers never leave a partial file (io.h, src/io/atomic_file): the CLI killed with
// SIGKILL in the middle of writing a large output, when no cleanup code can run, leaves
// at the target either no file or the previous complete one. Only its temporary file
// (".NAME.tmp.XXXXXX" beside the target) is left behind, under a name no reader takes
// for the output.
#include "test_support.h"

#include "meander/io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace meander {
namespace {

namespace fs = std::filesystem;

// The size of the first temporary file of `target` in its folder, or 0.
uintmax_t temporary_size(const fs::path& target) {
  // Appended rather than "." + name, which GCC 12 warns about wrongly (-Wrestrict).
  std::string prefix = ".";
  prefix += target.filename().string();
  prefix += ".tmp.";
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(target.parent_path()))
    if (entry.path().filename().string().starts_with(prefix)) {
      // Renamed away since the listing: file_size then fails and gives uintmax_t(-1).
      const uintmax_t size = entry.file_size(error);
      return error ? 0 : size;
    }
  return 0;
}

// Runs `meander generate sphere` of about a million faces (an OBJ of ~40 MB) into
// `target` and kills it once its temporary file holds a megabyte. Returns whether it was
// killed while writing (and not finished or failed first).
bool kill_while_writing(const fs::path& target) {
  const std::string cli = MEANDER_CLI;
  std::vector<std::string> args = {cli, "generate", "sphere", "--faces", "1000000", "-o", target.string()};
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(cli.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  while (temporary_size(target) < (uintmax_t(1) << 20)) {
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

TEST(AtomicFile, KilledMidWriteLeavesNoFile) {
  const fs::path target = test::output_dir() / "big.obj";
  ASSERT_TRUE(kill_while_writing(target));
  EXPECT_FALSE(fs::exists(target));
}

TEST(AtomicFile, KilledMidWriteLeavesThePreviousFileWhole) {
  const fs::path target = test::output_dir() / "big.obj";
  ASSERT_EQ(test::run_cli({"generate", "sphere", "--faces", "100", "-o", target.string()}).exit_code, 0);
  const std::string previous = test::read_file(target);
  ASSERT_FALSE(previous.empty());
  ASSERT_TRUE(kill_while_writing(target));
  EXPECT_EQ(test::read_file(target), previous);
}

// A large target is swapped with the new file and the previous one removed by a detached
// process (src/io/atomic_file.cpp): the target is the new file as soon as the writer
// returns, and the previous one is soon gone, leaving nothing beside it.
TEST(AtomicFile, LargeTargetIsReplacedAndThePreviousFileRemoved) {
  const fs::path dir = test::output_dir() / "replaced";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "curve.ply";
  for (const float x : {1.0f, 2.0f}) {
    Polylines curve;
    curve.points.assign(4'000'000, Vec3{x, 0, 0}); // 80 MB as a PLY: more than the 64 MiB swapped
    curve.start = {0, int32_t(curve.points.size())};
    write_polylines(curve, target);
    const Polylines read = read_polylines(target);
    ASSERT_EQ(read.points.size(), curve.points.size());
    EXPECT_EQ(read.points.front().x, x);
  }
  size_t files = 0;
  for (int wait = 0; wait < 100; ++wait) {
    files = size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
    if (files == 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(files, 1u);
}

// A PLY curve's blocks are reserved at its final size before its bytes are written, and
// never past it (AtomicFile::expect_size), so that closing it cuts nothing back: on ext4
// with `discard` that cut waited for the journal, behind the discards of the file the
// previous run had replaced (0.9 s at the end of the 10M curve). Watched from another
// thread while the file is written, its temporary file is never longer than the result.
TEST(AtomicFile, CurveFileIsNeverReservedPastItsSize) {
  const fs::path dir = test::output_dir() / "reserved";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "curve.ply";
  Polylines curve;
  curve.points.assign(5'000'000, Vec3{1, 2, 3}); // 100 MB: more than a step of 64 MiB
  curve.start = {0, 2'000'000, int32_t(curve.points.size())};
  std::atomic<bool> done = false;
  std::thread writer([&] {
    write_polylines(curve, target);
    done = true;
  });
  uintmax_t longest = 0;
  while (!done) {
    longest = std::max(longest, temporary_size(target));
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  writer.join();
  const uintmax_t size = fs::file_size(target);
  EXPECT_GT(longest, 0u); // the temporary file was seen
  EXPECT_LE(longest, size);
  EXPECT_EQ(read_polylines(target).points.size(), curve.points.size());
}

// A curve's points and edges are written around the page cache (O_DIRECT, AtomicFile::
// fill): once written, almost none of the file's pages are cached, where the page cache
// would hold its last 128 MiB, here the whole file. The header is 186 bytes (8-digit
// counts), so every float of the points lies 2 bytes off a multiple of 4, and records are
// cut at every buffer's end: read back, it is still the curve.
TEST(AtomicFile, LargeCurveIsWrittenAroundThePageCache) {
  const fs::path dir = test::output_dir() / "direct";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "curve.ply";
  if (const int probe = ::open((dir / "probe").c_str(), O_WRONLY | O_CREAT | O_DIRECT, 0644); probe < 0)
    GTEST_SKIP() << dir << " refuses O_DIRECT: everything goes through the page cache there";
  else
    ::close(probe);
  Polylines curve;
  for (int32_t i = 0; i < 10'000'000; ++i) curve.points.push_back({float(i), float(i % 7), -float(i)});
  curve.start = {0, 3'000'001, 7'654'321, int32_t(curve.points.size())};
  write_polylines(curve, target);

  const int fd = ::open(target.c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  const size_t size = size_t(fs::file_size(target));
  void* mapped = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
  ASSERT_NE(mapped, MAP_FAILED);
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> resident((size + page - 1) / page);
  ASSERT_EQ(::mincore(mapped, size, resident.data()), 0);
  ::munmap(mapped, size);
  ::close(fd);
  const auto cached = std::count_if(resident.begin(), resident.end(), [](unsigned char r) { return r & 1; });
  EXPECT_LT(size_t(cached), resident.size() / 100) << cached << " of " << resident.size() << " pages cached";

  const Polylines read = read_polylines(target);
  EXPECT_EQ(read.start, curve.start);
  EXPECT_TRUE(read.points == curve.points);
}

} // namespace
} // namespace meander
