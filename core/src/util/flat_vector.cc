// SPDX-License-Identifier: AGPL-3.0-or-later
#include "util/flat_vector.h"

#include <sys/mman.h>

#include <atomic>

namespace dot {
namespace {

constexpr size_t kHuge = size_t{2} << 20;
constexpr size_t kMapped = size_t{1} << 20;  // smaller blocks: operator new
std::atomic<TableMeter> meter{nullptr};

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kMap = false;  // ASan checks tables only from its heap
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kMap = false;
#else
constexpr bool kMap = true;
#endif
#else
constexpr bool kMap = true;
#endif

size_t Rounded(size_t bytes) { return (bytes + kHuge - 1) & ~(kHuge - 1); }

}  // namespace

void* AllocateTable(size_t bytes) {
  if (!kMap || bytes < kMapped) return ::operator new(bytes);
  // Map kHuge more, keep the 2 MiB-aligned part, return the rest at once.
  const size_t size = Rounded(bytes);
  void* raw = ::mmap(nullptr, size + kHuge, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto begin = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (begin + kHuge - 1) & ~(kHuge - 1);
  if (aligned > begin) ::munmap(raw, aligned - begin);
  const uintptr_t end = aligned + size;
  if (begin + size + kHuge > end) {
    ::munmap(reinterpret_cast<void*>(end), begin + size + kHuge - end);
  }
  void* p = reinterpret_cast<void*>(aligned);
  // Advice only: where the kernel has no THP, pages stay 4 KiB.
  ::madvise(p, size, MADV_HUGEPAGE);
  if (TableMeter m = meter.load(std::memory_order_relaxed)) {
    m(static_cast<int64_t>(bytes));
  }
  return p;
}

void FreeTable(void* p, size_t bytes) noexcept {
  if (p == nullptr) return;
  if (!kMap || bytes < kMapped) {
    ::operator delete(p);
    return;
  }
  ::munmap(p, Rounded(bytes));
  if (TableMeter m = meter.load(std::memory_order_relaxed)) {
    m(-static_cast<int64_t>(bytes));
  }
}

void SetTableMeter(TableMeter m) { meter.store(m); }

}  // namespace dot
