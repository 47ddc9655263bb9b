// SPDX-License-Identifier: AGPL-3.0-or-later
#include "heap_meter.h"

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "util/flat_vector.h"

namespace dot::bench {
namespace {

std::atomic<int64_t> live{0}, peak{0}, base{0};

void Count(int64_t bytes) {
  const int64_t now = live.fetch_add(bytes, std::memory_order_relaxed) + bytes;
  int64_t high = peak.load(std::memory_order_relaxed);
  while (now > high &&
         !peak.compare_exchange_weak(high, now, std::memory_order_relaxed)) {
  }
}

// The core maps its large tables itself (util/flat_vector.h): counted here
// as the heap they replace.
const bool metered = (SetTableMeter(&Count), true);

void* Allocate(size_t size) {
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  Count(static_cast<int64_t>(malloc_usable_size(p)));
  return p;
}

void Free(void* p) {
  if (p == nullptr) return;
  live.fetch_sub(static_cast<int64_t>(malloc_usable_size(p)),
                 std::memory_order_relaxed);
  std::free(p);
}

}  // namespace

void ResetHeapPeak() {
  const int64_t now = live.load();
  base = now;
  peak = now;
}

int64_t HeapPeakBytes() { return peak.load() - base.load(); }

}  // namespace dot::bench

// The replacements (C++17 [new.delete]); aligned forms are not used by the
// code measured here and keep the library's.
void* operator new(size_t size) { return dot::bench::Allocate(size); }
void* operator new[](size_t size) { return dot::bench::Allocate(size); }
void operator delete(void* p) noexcept { dot::bench::Free(p); }
void operator delete[](void* p) noexcept { dot::bench::Free(p); }
void operator delete(void* p, size_t) noexcept { dot::bench::Free(p); }
void operator delete[](void* p, size_t) noexcept { dot::bench::Free(p); }
void* operator new(size_t size, const std::nothrow_t&) noexcept {
  try {
    return dot::bench::Allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](size_t size, const std::nothrow_t&) noexcept {
  try {
    return dot::bench::Allocate(size);
  } catch (...) {
    return nullptr;
  }
}
