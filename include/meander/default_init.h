// Vectors whose elements are not zeroed when they are sized.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace meander {

// std::allocator, except that an element made without a value (resize(n)) is left
// uninitialised, for the large arrays that are written whole right after they are sized:
// zeroing one first is a serial pass over it (docs/curve.md, "Large meshes").
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    std::construct_at(p, std::forward<Args>(args)...);
  }
};

template <typename T>
using UninitVector = std::vector<T, DefaultInitAllocator<T>>;

} // namespace meander
