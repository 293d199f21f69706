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
#include <cstdint>
#include <cstdlib>
#include <new>

#include <sys/mman.h>

namespace {

constexpr size_t kLargeBlock = size_t(4) << 20;
constexpr uintptr_t kPage = 4096;

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
