// Large allocations of the CLI on transparent huge pages.
//
// Wires of millions of triangles make the printability report (and the curve stages
// before it) allocate gigabytes of fresh arrays. Where the kernel gives huge pages only
// on request (/sys/kernel/mm/transparent_hugepage/enabled = madvise, as on the guests
// docs/benchmarks.md describes), each 4 KiB page is faulted in and cleared separately:
// about 14 us a page there, seconds per gigabyte, a quarter of the report's CPU time on a
// 19 M-triangle wire. Asking for huge pages on every large block cuts the faults by a
// factor of ten and changes nothing else. It is done here, for the whole program, since
// the arrays are plain std::vectors all over the library; a library user chooses for
// their own program (e.g. GLIBC_TUNABLES=glibc.malloc.hugetlb=1 does the same).
#include <sys/mman.h>

#include <cstdlib>
#include <new>

// Under AddressSanitizer its own operator new stays, to check that new and delete pair up.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MEANDER_ASAN 1
#endif
#endif
#if !defined(__SANITIZE_ADDRESS__) && !defined(MEANDER_ASAN)

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;
// Below this, blocks come from malloc's heap as usual (a huge page each would waste memory).
constexpr std::size_t kLargeBlock = std::size_t(4) << 20;

void* allocate(std::size_t size) {
  if (size >= kLargeBlock) {
    const std::size_t rounded = (size + kHugePage - 1) / kHugePage * kHugePage;
    if (void* p = std::aligned_alloc(kHugePage, rounded)) {
#ifdef MADV_HUGEPAGE
      madvise(p, rounded, MADV_HUGEPAGE); // advice only: on failure the pages stay small
#endif
      return p;
    }
    throw std::bad_alloc();
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

} // namespace

// The replaceable global allocation functions ([new.delete.single], [new.delete.array]);
// the aligned and nothrow forms keep their defaults, which also use malloc and free.
void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

#endif
