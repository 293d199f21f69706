// Vectors whose elements are not zeroed when they are sized, large ones on huge pages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace meander {

// Blocks of this size or more are aligned to a 2 MiB page and advised onto transparent
// huge pages: random access into the large arrays then misses the TLB far less, and
// kernels that give huge pages only to memory that asks (Debian's, `madvise`) give none
// otherwise. Only these arrays are advised; the global allocator stays the host's.
inline constexpr size_t kHugePageBlock = size_t(4) << 20;
inline constexpr std::align_val_t kHugePageAlignment{size_t(2) << 20};

// Advises the 2 MiB-aligned [block, block + bytes) onto transparent huge pages. Advice
// only: where the system has none or refuses, nothing changes.
void advise_huge_pages(void* block, size_t bytes) noexcept;

// std::allocator, except that an element made without a value (resize(n)) is left
// uninitialised, for the large arrays that are written whole right after they are sized:
// zeroing one first is a serial pass over it (docs/curve.md, "Large meshes").
// Blocks of kHugePageBlock bytes or more come from the aligned operator new and are
// advised onto huge pages; deallocate tells them apart by the same size.
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    if (!huge(n)) return std::allocator<T>::allocate(n);
    void* block = ::operator new(n * sizeof(T), kHugePageAlignment);
    advise_huge_pages(block, n * sizeof(T));
    return static_cast<T*>(block);
  }
  void deallocate(T* p, size_t n) noexcept {
    if (huge(n)) ::operator delete(p, kHugePageAlignment); // unsized: clang before 19 has no sized delete by default
    else std::allocator<T>::deallocate(p, n);
  }

  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    std::construct_at(p, std::forward<Args>(args)...);
  }

private:
  // A count too large for memory is std::allocator's to refuse.
  static bool huge(size_t n) { return n <= SIZE_MAX / sizeof(T) && n * sizeof(T) >= kHugePageBlock; }
};

template <typename T>
using UninitVector = std::vector<T, DefaultInitAllocator<T>>;

} // namespace meander
