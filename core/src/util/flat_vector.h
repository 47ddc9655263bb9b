// SPDX-License-Identifier: AGPL-3.0-or-later
// Vectors for the large tables of a solve (adjacency, DP entries) and of
// the edge index. Their first touch was a fifth of a large solve: every
// 4 KiB page faults once, about 9 us each in a VM. TableAllocator puts
// every table of 64 KiB or more on transparent huge pages (madvise; THP
// "madvise" or "always" grants them), in every entry point, with no
// environment variable: tables up to 1 MiB share 2 MiB chunks, cut into
// blocks of one size class each (four per doubling); larger ones are
// mapped alone from a 2 MiB boundary, so each whole 2 MiB faults once. A
// table's partial last 2 MiB is a huge page too where that adds at most a
// quarter to the table (or the table is under 2 MiB), else it stays on
// 4 KiB pages.
// SetTableMeter lets a heap meter count these blocks, and
// SetTableCacheBytes keeps freed ones warm for the next solve.
// FlatVector is the same with resize() leaving trivial elements
// uninitialized: DP tables are written before they are read, and
// zero-filling them first costs a page-faulting pass no cancel flag can
// interrupt.
#ifndef DOT_CORE_UTIL_FLAT_VECTOR_H_
#define DOT_CORE_UTIL_FLAT_VECTOR_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "dot/table_memory.h"

namespace dot {

// Blocks from this size on are on huge pages; smaller ones come from
// operator new.
inline constexpr size_t kPoolBytes = size_t{64} << 10;
// A huge page.
inline constexpr size_t kTableHugeBytes = size_t{2} << 20;
// Sanitizers watch the heap (ASan its bounds, MSan what is initialized,
// TSan its races): their builds keep every table there.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kMapTables = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(thread_sanitizer)
inline constexpr bool kMapTables = false;
#else
inline constexpr bool kMapTables = true;
#endif
#else
inline constexpr bool kMapTables = true;
#endif
// A block for a table: from operator new below kPoolBytes (and in
// sanitizer builds, which watch the heap), else on huge pages.
// Throws std::bad_alloc when the kernel refuses. Free with the same size.
void* AllocateTable(size_t bytes);
void FreeTable(void* p, size_t bytes) noexcept;
// The bytes a table of `bytes` holds: its size class in the pool, its
// mapping rounded to pages, or `bytes` from operator new.
size_t TableFootprint(size_t bytes);
// The bytes of the pool's 2 MiB chunks, in use or kept empty.
size_t TablePoolBytes();
// Called with +footprint / -footprint for every block on huge pages (not
// for those from operator new, which a replaced operator new sees): for
// heap meters.
using TableMeter = void (*)(int64_t delta);
void SetTableMeter(TableMeter meter);
// SetTableCacheBytes (dot/table_memory.h) keeps freed mapped blocks.

// C++17's std::vector calls allocate and deallocate only (C++23's
// allocate_at_least would bypass them: the project builds C++17).
template <typename T>
struct TableAllocator : std::allocator<T> {
  static_assert(alignof(T) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__,
                "operator new(size) would not align T");
  template <typename U>
  struct rebind {
    using other = TableAllocator<U>;
  };
  TableAllocator() = default;
  template <typename U>
  TableAllocator(const TableAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    if (n > SIZE_MAX / sizeof(T)) throw std::bad_alloc();
    return static_cast<T*>(AllocateTable(n * sizeof(T)));
  }
  void deallocate(T* p, size_t n) noexcept { FreeTable(p, n * sizeof(T)); }
};

template <typename T>
struct DefaultInitAllocator : TableAllocator<T> {
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

// A table: value-initialized like std::vector, on huge pages when large.
template <typename T>
using Table = std::vector<T, TableAllocator<T>>;
// A table whose resize() leaves trivial elements uninitialized.
template <typename T>
using FlatVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace dot

#endif  // DOT_CORE_UTIL_FLAT_VECTOR_H_
