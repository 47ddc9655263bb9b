// SPDX-License-Identifier: AGPL-3.0-or-later
#include "util/flat_vector.h"

#include <sys/mman.h>

#include <atomic>
#include <mutex>
#include <vector>

namespace dot {
namespace {

constexpr size_t kHuge = size_t{2} << 20;
constexpr size_t kPage = 4096;
std::atomic<TableMeter> meter{nullptr};

// A table's mapped size. Whole huge pages where that adds at most a
// quarter (a table of 8 MiB or more always): the whole table faults in
// 2 MiB at a time. Else whole 4 KiB pages: the partial last 2 MiB stays on
// small pages, and the table holds no more than it touches.
size_t Rounded(size_t bytes) {
  const size_t huge = (bytes + kHuge - 1) & ~(kHuge - 1);
  if (huge - bytes <= bytes / 4) return huge;
  return (bytes + kPage - 1) & ~(kPage - 1);
}

// Freed blocks kept for reuse, up to `limit` bytes in all, oldest first.
// Few tables live at once, so a short list under a mutex does.
struct Cache {
  std::mutex mutex;
  size_t limit = 0, held = 0;
  std::vector<std::pair<void*, size_t>> blocks;  // start, mapped size

  void DropOldest() {
    ::munmap(blocks.front().first, blocks.front().second);
    held -= blocks.front().second;
    blocks.erase(blocks.begin());
  }
  // The smallest kept block of `size` to twice that (a larger one would
  // waste its warm tail), its tail beyond `size` unmapped. On a miss, kept
  // blocks of `size` bytes in all go back to the kernel first: the new
  // table replaces them.
  void* Take(size_t size) {
    std::lock_guard<std::mutex> lock(mutex);
    size_t best = blocks.size();
    for (size_t i = 0; i < blocks.size(); ++i) {
      const size_t s = blocks[i].second;
      if (s >= size && s <= 2 * size + kHuge &&
          (best == blocks.size() || s < blocks[best].second)) {
        best = i;
      }
    }
    if (best == blocks.size()) {
      for (size_t freed = 0; freed < size && !blocks.empty();) {
        freed += blocks.front().second;
        DropOldest();
      }
      return nullptr;
    }
    auto [p, mapped] = blocks[best];
    blocks.erase(blocks.begin() + static_cast<ptrdiff_t>(best));
    held -= mapped;
    if (mapped > size) ::munmap(static_cast<char*>(p) + size, mapped - size);
    return p;
  }
  // Keeps the block when it fits under the limit (dropping older ones).
  bool Keep(void* p, size_t size) noexcept {
    std::lock_guard<std::mutex> lock(mutex);
    if (size > limit) return false;
    while (held + size > limit && !blocks.empty()) DropOldest();
    try {
      blocks.emplace_back(p, size);
    } catch (const std::bad_alloc&) {
      return false;
    }
    held += size;
    return true;
  }
  void Trim(size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex);
    while (held > bytes) DropOldest();
  }
};

Cache& TheCache() {
  static Cache* cache = new Cache;  // outlives every table, also at exit
  return *cache;
}

void* Map(size_t size) {
  // Map kHuge more, keep the 2 MiB-aligned part, return the rest at once.
  // No MAP_NORESERVE: a table the machine cannot hold is refused here
  // (bad_alloc, then RESOURCE_EXHAUSTED), not killed when touched.
  void* raw = ::mmap(nullptr, size + kHuge, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
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
  return p;
}

}  // namespace

void* AllocateTable(size_t bytes) {
  if (!kMapTables || bytes < kTableMapBytes) return ::operator new(bytes);
  if (bytes > SIZE_MAX - kHuge) throw std::bad_alloc();
  const size_t size = Rounded(bytes);
  void* p = TheCache().Take(size);
  if (p == nullptr) p = Map(size);
  if (TableMeter m = meter.load(std::memory_order_relaxed)) {
    m(static_cast<int64_t>(bytes));
  }
  return p;
}

void FreeTable(void* p, size_t bytes) noexcept {
  if (p == nullptr) return;
  if (!kMapTables || bytes < kTableMapBytes) {
    ::operator delete(p);
    return;
  }
  if (!TheCache().Keep(p, Rounded(bytes))) ::munmap(p, Rounded(bytes));
  if (TableMeter m = meter.load(std::memory_order_relaxed)) {
    m(-static_cast<int64_t>(bytes));
  }
}

void SetTableMeter(TableMeter m) { meter.store(m); }

void SetTableCacheBytes(size_t bytes) {
  Cache& cache = TheCache();
  {
    std::lock_guard<std::mutex> lock(cache.mutex);
    cache.limit = bytes;
  }
  cache.Trim(bytes);
}

size_t TableCacheBytesHeld() {
  Cache& cache = TheCache();
  std::lock_guard<std::mutex> lock(cache.mutex);
  return cache.held;
}

void TrimTableCache(size_t bytes) { TheCache().Trim(bytes); }

}  // namespace dot
