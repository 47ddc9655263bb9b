// SPDX-License-Identifier: AGPL-3.0-or-later
#include "util/flat_vector.h"

#include <sys/mman.h>

#include <atomic>
#include <mutex>
#include <vector>

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

// Freed blocks kept for reuse, up to `limit` bytes in all. Few tables
// live at once, so a short list under a mutex does.
struct Cache {
  std::mutex mutex;
  size_t limit = 0, held = 0;
  std::vector<std::pair<void*, size_t>> blocks;  // start, mapped size

  // The smallest kept block of at least `size`, its tail beyond `size`
  // unmapped; null when none.
  void* Take(size_t size) {
    std::lock_guard<std::mutex> lock(mutex);
    size_t best = blocks.size();
    for (size_t i = 0; i < blocks.size(); ++i) {
      if (blocks[i].second >= size &&
          (best == blocks.size() || blocks[i].second < blocks[best].second)) {
        best = i;
      }
    }
    if (best == blocks.size()) return nullptr;
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
    while (held + size > limit && !blocks.empty()) {
      ::munmap(blocks.front().first, blocks.front().second);
      held -= blocks.front().second;
      blocks.erase(blocks.begin());
    }
    try {
      blocks.emplace_back(p, size);
    } catch (const std::bad_alloc&) {
      return false;
    }
    held += size;
    return true;
  }
  void SetLimit(size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex);
    limit = bytes;
    while (held > limit) {
      ::munmap(blocks.front().first, blocks.front().second);
      held -= blocks.front().second;
      blocks.erase(blocks.begin());
    }
  }
};

Cache& TheCache() {
  static Cache* cache = new Cache;  // outlives every table, also at exit
  return *cache;
}

void* Map(size_t size) {
  // Map kHuge more, keep the 2 MiB-aligned part, return the rest at once.
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
  return p;
}

}  // namespace

void* AllocateTable(size_t bytes) {
  if (!kMap || bytes < kMapped) return ::operator new(bytes);
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
  if (!kMap || bytes < kMapped) {
    ::operator delete(p);
    return;
  }
  if (!TheCache().Keep(p, Rounded(bytes))) ::munmap(p, Rounded(bytes));
  if (TableMeter m = meter.load(std::memory_order_relaxed)) {
    m(-static_cast<int64_t>(bytes));
  }
}

void SetTableMeter(TableMeter m) { meter.store(m); }

void SetTableCacheBytes(size_t bytes) { TheCache().SetLimit(bytes); }

}  // namespace dot
