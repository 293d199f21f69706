// Large arrays on transparent huge pages where they pay, for the programs that process
// whole meshes (the CLI and the benchmarks), not for the library: a library must not
// replace its host's operator new.
//
// A 10M-triangle curve touches about 1.3 GB of fresh memory. In 4 KiB pages that is
// 550,000 page faults and as many TLB misses on every random access into the quad and
// halfedge arrays; measured on the 10M sphere, the run spent more CPU time in faults and
// TLB misses than in the algorithms. Debian's kernel gives huge pages only to memory that
// asks for them (transparent_hugepage=madvise), and glibc asks only when started with
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1, which a program cannot set for itself once it
// runs. So blocks of 4 MiB and more are advised here, whether glibc serves them from its
// heap (under 32 MiB, below) or with their own mmap, which free() unmaps as usual: onto
// huge pages on the hosts where those cost less (page_sizes.h).
//
// Memory given back to the kernel costs a page fault per 4 KiB page when it is taken
// again, and on this project's machines (virtual, with paravirtualised page tables) a
// fault costs ~20 us: reading the 70k-triangle bunny and building its connectivity took
// 22 ms when done repeatedly in one process (the benchmarks, the studio's server), 14 of
// them in the faults of the heap that glibc had trimmed after the previous mesh. So freed
// memory below 256 MiB stays with the process, and blocks under 32 MiB come from the heap
// (glibc's default policy moves towards these values itself, but only after a large
// block was freed, and trims to twice the largest one freed). The heap holds every
// array of a mesh up to about 2.7M triangles, several at once: a 1M-triangle mesh read
// and connected takes 67 MiB of it, and with 64 MiB kept glibc gave that back after each
// mesh, 180,000 page faults in a benchmark loop where 6,700 remain now (docs/benchmarks.md).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <system_error>
#include <thread>

#include "page_sizes.h"

#include <malloc.h>
#include <sys/mman.h>

namespace {

constexpr size_t kLargeBlock = size_t(4) << 20;
constexpr uintptr_t kPrefaultStep = 2 * meander::PageSizes::kHugePage;
constexpr uintptr_t kPage = 4096;
constexpr int kHeapBlockLimit = 32 << 20;
constexpr int kKeptFreeMemory = 256 << 20;

using meander::PageSizes;
constinit PageSizes page_sizes;

const bool kKeepFreedMemory = [] {
  mallopt(M_MMAP_THRESHOLD, kHeapBlockLimit);
  mallopt(M_TRIM_THRESHOLD, kKeptFreeMemory);
  return true;
}();

// Faults a block's pages in on two threads before the caller's first write, and touches
// each page once from user space. std::vector zeroes what it allocates on one thread, and
// on this project's virtual machines a fresh page can cost more than zeroing it: its host
// backs it only when it is first touched (after the guest has reported it free),
// measured at up to 2.3 s/GiB for huge pages. On two threads the 10M-triangle curve's
// check and quadrangulate took about 0.5 s less each in that state (docs/benchmarks.md).
// Every large block is faulted so, not only those of 64 MiB and more as before: `perf`
// then found the run's remaining one-core stretches (0.1 s each) in the zeroing of blocks
// of 19 to 57 MiB. And the threads take steps of two huge pages in turn rather than half
// the block each: some pages are still backed and cost nothing, and a thread left with
// the other half's fresh ones faulted alone while the other waited. The block is taken
// whole, so a vector's capacity beyond its size is resident too (the duotone of a
// 1M-triangle sphere: 89 MB more at its peak, 6.5 %). The touch from user space puts
// into the time what a host may still charge at a page's first use by the program
// (page_sizes.h). Advice only: a kernel without MADV_POPULATE_WRITE (before 5.14)
// leaves the pages to the touch.
void prefault(uintptr_t begin, uintptr_t end) {
  const uintptr_t first = begin & ~(kPrefaultStep - 1);
  std::atomic<uintptr_t> next{0};
  const auto populate = [&] {
    for (uintptr_t step; first + (step = next.fetch_add(1, std::memory_order_relaxed)) * kPrefaultStep < end;) {
      const uintptr_t from = std::max(begin, first + step * kPrefaultStep);
      const uintptr_t to = std::min(end, first + (step + 1) * kPrefaultStep);
      madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
      for (uintptr_t page = from; page < to; page += kPage) {
        auto* byte = reinterpret_cast<volatile unsigned char*>(page);
        *byte = *byte; // the block is the caller's to be: its bytes are not yet anyone's
      }
    }
  };
  try {
    std::thread other(populate);
    populate();
    other.join();
  } catch (const std::system_error&) { // no thread to be had: all on this one
    populate();
  }
}

// Advises [begin, end) onto pages of `size` (advice only: where the kernel refuses, the
// pages stay small) and faults them in, telling `page_sizes` what that cost.
void take(uintptr_t begin, uintptr_t end, PageSizes::Size size) {
  if (end <= begin) return;
  madvise(reinterpret_cast<void*>(begin), end - begin, size == PageSizes::huge ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);
  const auto start = std::chrono::steady_clock::now();
  prefault(begin, end);
  page_sizes.record(size, end - begin, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

void* allocate(size_t size) {
  void* block = std::malloc(size == 0 ? 1 : size);
  if (block == nullptr) throw std::bad_alloc();
  if (size >= kLargeBlock) {
    // Whole pages inside the block only: its first page holds malloc's header.
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(block) + kPage - 1) & ~(kPage - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(block) + size) & ~(kPage - 1);
    if (end > begin) {
      const uintptr_t split = page_sizes.split(begin, end);
      take(begin, split, PageSizes::huge);
      take(split, end, PageSizes::small);
    }
  }
  return block;
}

} // namespace

// The array forms and the sized and nothrow deletes of libstdc++ call these two.
void* operator new(size_t size) { return allocate(size); }
void operator delete(void* block) noexcept { std::free(block); }
