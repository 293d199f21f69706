// meander_bench_floors [--memory-gb G] [--write FILE --write-gb W]: what this machine
// charges for the work every large run does whatever its algorithms: touching fresh
// memory (a first write to each page, in 4 KiB pages and in transparent huge pages) and
// writing a large file. On a virtual machine whose host backs guest memory lazily a
// fresh page costs far more than writing to it; these floors bound from below what any
// program of the same footprint and output size can reach here (docs/benchmarks.md).
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Seconds per GiB to map fresh anonymous memory and write one byte per 4 KiB page, then
// to write it all again (the cost once the pages exist).
void touch_memory(size_t bytes, bool huge) {
  const Clock::time_point start = Clock::now();
  void* mapped = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) {
    std::perror("mmap");
    std::exit(1);
  }
  char* p = static_cast<char*>(mapped);
  if (huge) madvise(p, bytes, MADV_HUGEPAGE);
  for (size_t i = 0; i < bytes; i += 4096) p[i] = 1;
  const double first = seconds_since(start);
  const Clock::time_point again = Clock::now();
  std::memset(p, 2, bytes);
  const double second = seconds_since(again);
  munmap(p, bytes);
  const double gib = double(bytes) / double(1 << 30);
  std::printf("| fresh memory, %s pages | %.2f s/GiB | %.2f s/GiB |\n", huge ? "2 MiB (advised)" : "4 KiB", first / gib,
              second / gib);
}

// Seconds per GiB to write `bytes` to `path` in 64 MiB blocks and close it (the page
// cache takes it; nothing waits for the disk), then remove the file.
void write_file(const std::string& path, size_t bytes) {
  std::vector<char> block(size_t(64) << 20, 'x');
  const Clock::time_point start = Clock::now();
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    std::perror(path.c_str());
    std::exit(1);
  }
  for (size_t done = 0; done < bytes;) {
    const ssize_t n = write(fd, block.data(), std::min(block.size(), bytes - done));
    if (n <= 0) {
      std::perror("write");
      std::exit(1);
    }
    done += size_t(n);
  }
  close(fd);
  const double seconds = seconds_since(start);
  unlink(path.c_str());
  std::printf("| writing a %.2f GiB file | %.2f s/GiB | |\n", double(bytes) / double(1 << 30),
              seconds / (double(bytes) / double(1 << 30)));
}

} // namespace

int main(int argc, char** argv) {
  double memory_gib = 1, write_gib = 0;
  std::string write_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view flag = argv[i];
    if (flag == "--memory-gb") memory_gib = std::atof(argv[i + 1]);
    else if (flag == "--write") write_path = argv[i + 1];
    else if (flag == "--write-gb") write_gib = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: meander_bench_floors [--memory-gb G] [--write FILE --write-gb W]\n");
      return 2;
    }
  }
  std::printf("| what | first time | again |\n|---|---:|---:|\n");
  touch_memory(size_t(memory_gib * double(1 << 30)), false);
  touch_memory(size_t(memory_gib * double(1 << 30)), true);
  if (!write_path.empty() && write_gib > 0) write_file(write_path, size_t(write_gib * double(1 << 30)));
  return 0;
}
