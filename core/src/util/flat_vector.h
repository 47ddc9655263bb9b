// SPDX-License-Identifier: AGPL-3.0-or-later
// std::vector whose resize() leaves trivial elements uninitialized. Large DP
// tables are written before they are read; zero-filling them first costs a
// page-faulting pass over hundreds of MB that no cancel flag can interrupt.
#ifndef DOT_CORE_UTIL_FLAT_VECTOR_H_
#define DOT_CORE_UTIL_FLAT_VECTOR_H_

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace dot {

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
  void construct(U* p) noexcept(noexcept(U())) {
    ::new (static_cast<void*>(p)) U;  // default-init: no zeroing
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <typename T>
using FlatVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace dot

#endif  // DOT_CORE_UTIL_FLAT_VECTOR_H_
