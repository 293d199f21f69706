// Large arrays on transparent huge pages, for the programs that process whole meshes (the
// CLI and the benchmarks), not for the library: a library must not replace its host's
// operator new.
//
// A 10M-triangle curve touches about 1.3 GB of fresh memory. In 4 KiB pages that is
// 550,000 page faults and as many TLB misses on every random access into the quad and
// halfedge arrays; measured on the 10M sphere, the run spent more CPU time in faults and
// TLB misses than in the algorithms. Debian's kernel gives huge pages only to memory that
// asks for them (transparent_hugepage=madvise), and glibc asks only when started with
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1, which a program cannot set for itself once it
// runs. So blocks of 4 MiB and more are advised here: glibc serves them with their own
// mmap, untouched apart from their first page, and free() unmaps them as usual.
//
// Memory given back to the kernel costs a page fault per 4 KiB page when it is taken
// again, and on this project's machines (virtual, with paravirtualised page tables) a
// fault costs ~20 us: reading the 70k-triangle bunny and building its connectivity took
// 22 ms when done repeatedly in one process (the benchmarks, the studio's server), 14 of
// them in the faults of the heap that glibc had trimmed after the previous mesh. So freed
// memory below 64 MiB stays with the process, and blocks under 32 MiB come from the heap
// (glibc's default policy moves towards these values itself, but only after a large
// block was freed, and trims to twice the largest one freed).
#include <cstdint>
#include <cstdlib>
#include <new>

#include <malloc.h>
#include <sys/mman.h>

namespace {

constexpr size_t kLargeBlock = size_t(4) << 20;
constexpr uintptr_t kPage = 4096;
constexpr int kHeapBlockLimit = 32 << 20;
constexpr int kKeptFreeMemory = 64 << 20;

const bool kKeepFreedMemory = [] {
  mallopt(M_MMAP_THRESHOLD, kHeapBlockLimit);
  mallopt(M_TRIM_THRESHOLD, kKeptFreeMemory);
  return true;
}();

void* allocate(size_t size) {
  void* block = std::malloc(size == 0 ? 1 : size);
  if (block == nullptr) throw std::bad_alloc();
  if (size >= kLargeBlock) {
    // Whole pages inside the block only: its first page holds malloc's header.
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(block) + kPage - 1) & ~(kPage - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(block) + size) & ~(kPage - 1);
    // Advice only: where the kernel refuses, the block keeps small pages.
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
  return block;
}

} // namespace

// The array forms and the sized and nothrow deletes of libstdc++ call these two.
void* operator new(size_t size) { return allocate(size); }
void operator delete(void* block) noexcept { std::free(block); }
