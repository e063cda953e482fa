#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace lfsp {

// A std::vector whose new elements of trivial types are left uninitialised (default- instead of value-initialised):
// `UninitializedVector<float> v(n)` costs no zero fill, and its pages are first touched by whoever writes them. For
// the 4D buffers that a parallel loop writes in full right after sizing them (LFSP's 255 MB of Lab samples on
// 9x9x512x512), a zero fill first is a serial pass over all of it, page faults included. Sizing with a value
// (`v(n, x)`) still fills.
template <typename T, typename Base = std::allocator<T>>
class DefaultInitAllocator : public Base {
  using Traits = std::allocator_traits<Base>;

 public:
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U, typename Traits::template rebind_alloc<U>>;
  };
  using Base::Base;
  template <typename U>
  void construct(U* place) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(place)) U;
  }
  template <typename U, typename... Args>
  void construct(U* place, Args&&... args) {
    Traits::construct(static_cast<Base&>(*this), place, std::forward<Args>(args)...);
  }
};

template <typename T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace lfsp
