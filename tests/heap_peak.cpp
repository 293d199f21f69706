#include "heap_peak.h"

#include <atomic>
#include <cstdlib>
#include <malloc.h>
#include <new>

namespace meander::test {
namespace {

std::atomic<size_t> live{0}, peak{0};

void* allocate(size_t size, size_t alignment) {
  for (;;) {
    void* p = alignment > alignof(std::max_align_t) ? std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment)
                                                    : std::malloc(size ? size : 1);
    if (p) {
      const size_t bytes = malloc_usable_size(p);
      const size_t now = live.fetch_add(bytes, std::memory_order_relaxed) + bytes;
      for (size_t seen = peak.load(std::memory_order_relaxed); now > seen && !peak.compare_exchange_weak(seen, now);) {
      }
      return p;
    }
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void release(void* p) noexcept {
  if (!p) return;
  live.fetch_sub(malloc_usable_size(p), std::memory_order_relaxed);
  std::free(p);
}

void* allocate_nothrow(size_t size, size_t alignment) noexcept {
  try {
    return allocate(size, alignment);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}

} // namespace

size_t reset_heap_peak() {
  const size_t now = live.load();
  peak.store(now);
  return now;
}
size_t heap_peak() { return peak.load(); }

} // namespace meander::test

using meander::test::allocate;
using meander::test::allocate_nothrow;
using meander::test::release;
constexpr size_t plain = alignof(std::max_align_t);

void* operator new(size_t size) { return allocate(size, plain); }
void* operator new[](size_t size) { return allocate(size, plain); }
void* operator new(size_t size, std::align_val_t a) { return allocate(size, size_t(a)); }
void* operator new[](size_t size, std::align_val_t a) { return allocate(size, size_t(a)); }
void* operator new(size_t size, const std::nothrow_t&) noexcept { return allocate_nothrow(size, plain); }
void* operator new[](size_t size, const std::nothrow_t&) noexcept { return allocate_nothrow(size, plain); }
void* operator new(size_t size, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate_nothrow(size, size_t(a)); }
void* operator new[](size_t size, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate_nothrow(size, size_t(a)); }
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, size_t) noexcept { release(p); }
void operator delete[](void* p, size_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, size_t, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
