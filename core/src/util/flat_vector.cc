// SPDX-License-Identifier: AGPL-3.0-or-later
#include "util/flat_vector.h"

#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace dot {
namespace {

constexpr size_t kHuge = kTableHugeBytes;
constexpr size_t kPage = 4096;
std::atomic<TableMeter> meter{nullptr};

// A table's mapped size. One whole huge page below 2 MiB (at most twice
// the table, as in the pool). Above, whole huge pages where that adds at
// most a quarter (a table of 8 MiB or more always): the whole table faults
// in 2 MiB at a time. Else whole 4 KiB pages: the partial last 2 MiB stays
// on small pages, and the table holds no more than it touches.
size_t Rounded(size_t bytes) {
  const size_t huge = (bytes + kHuge - 1) & ~(kHuge - 1);
  if (bytes < kHuge || huge - bytes <= bytes / 4) return huge;
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

// Tables of kPoolBytes to kPoolLargest share huge pages: a 2 MiB chunk
// (2 MiB-aligned) is cut into blocks of one size class, so the first table
// of a class faults once for the chunk instead of once per 4 KiB, and
// later ones find it warm. Four classes per doubling: a table holds at
// most a quarter more than it asks for (power-of-two classes made DOT2's
// peak heap 1.17 x CGAL's on holes of 1,000+ vertices; these, 0.95). A
// freed block serves the next table of its class (last freed first). Up
// to kKeptChunks chunks whose blocks are all free stay (32 MiB), as malloc
// keeps its heap: repeated solves in one process would otherwise fault and
// zero fresh chunks each time (twice the adjacency build's time at
// n = 1,024; a solve's tables span up to ten classes, and six kept chunks
// still doubled it at n = 4,096). Further empty chunks go back to the
// kernel. Chunks bypass the table cache, which keeps larger tables: a
// chunk taken from it would drop its oldest block on a miss.
constexpr size_t kPoolLargest = kHuge / 2;
constexpr int kClasses = 17;  // 64 KiB, 80 KiB, 92 KiB, 108 KiB, ..., 1 MiB
constexpr size_t kKeptChunks = 16;

constexpr size_t ClassBytes(int c) {
  constexpr size_t kFirstOctave[4] = {16, 20, 23, 27};  // 4 KiB pages
  return (kFirstOctave[c % 4] << (c / 4)) * kPage;
}
static_assert(ClassBytes(0) == kPoolBytes);
static_assert(ClassBytes(kClasses - 1) == kPoolLargest);

int ClassOf(size_t bytes) {
  int c = 0;
  while (ClassBytes(c) < bytes) ++c;
  return c;
}

struct Pool {
  std::mutex mutex;
  std::vector<void*> free[kClasses];  // room for every block of the class
  size_t chunks[kClasses] = {};
  size_t kept = 0;                               // chunks with no block out
  std::unordered_map<uintptr_t, uint32_t> held;  // chunk start -> blocks out

  static uintptr_t ChunkOf(void* p) {
    return reinterpret_cast<uintptr_t>(p) & ~(kHuge - 1);
  }
  void* Take(int c) {
    std::lock_guard<std::mutex> lock(mutex);
    if (free[c].empty()) {
      // Room for every block of the class first: Give cannot throw.
      const size_t block = ClassBytes(c);
      const size_t per_chunk = kHuge / block;
      free[c].reserve((chunks[c] + 1) * per_chunk);
      // Mapped here, not taken from the cache: a chunk would drop the
      // cache's oldest block on a miss, perhaps a large warm DP table.
      char* chunk = static_cast<char*>(Map(kHuge));
      try {
        held.emplace(reinterpret_cast<uintptr_t>(chunk), 0);
      } catch (...) {
        ::munmap(chunk, kHuge);
        throw;
      }
      ++chunks[c];
      for (size_t k = per_chunk; k > 0; --k) {
        free[c].push_back(chunk + (k - 1) * block);  // the start first
      }
    } else if (held.find(ChunkOf(free[c].back()))->second == 0) {
      --kept;  // a kept chunk is in use again
    }
    void* p = free[c].back();
    free[c].pop_back();
    ++held.find(ChunkOf(p))->second;  // its chunk is in the map
    return p;
  }
  void Give(void* p, int c) noexcept {
    std::lock_guard<std::mutex> lock(mutex);
    free[c].push_back(p);  // within the capacity reserved in Take
    auto it = held.find(ChunkOf(p));
    if (--it->second > 0) return;
    if (kept < kKeptChunks) {
      ++kept;
      return;
    }
    Release(it, c);
  }
  // Returns an empty chunk of class c to the kernel (its blocks leave the
  // free list); the kept chunks are the pool's warm memory, the cache is
  // for larger tables.
  void Release(std::unordered_map<uintptr_t, uint32_t>::iterator it,
               int c) noexcept {
    const uintptr_t chunk = it->first;
    held.erase(it);
    --chunks[c];
    auto& list = free[c];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](void* q) { return ChunkOf(q) == chunk; }),
               list.end());
    ::munmap(reinterpret_cast<void*>(chunk), kHuge);
  }
  size_t Bytes() {
    std::lock_guard<std::mutex> lock(mutex);
    return held.size() * kHuge;
  }
  // Returns the kept empty chunks to the kernel (TrimTableCache).
  void Trim() noexcept {
    std::lock_guard<std::mutex> lock(mutex);
    for (int c = 0; c < kClasses && kept > 0; ++c) {
      for (auto it = free[c].begin(); it != free[c].end();) {
        auto chunk = held.find(ChunkOf(*it));
        if (chunk->second != 0) {
          ++it;
          continue;
        }
        Release(chunk, c);  // erases from free[c]
        --kept;
        it = free[c].begin();
      }
    }
  }
};

Pool& ThePool() {
  static Pool* pool = new Pool;  // outlives every table, also at exit
  return *pool;
}

void Metered(int64_t delta) {
  if (TableMeter m = meter.load(std::memory_order_relaxed)) m(delta);
}

}  // namespace

size_t TableFootprint(size_t bytes) {
  if (!kMapTables || bytes < kPoolBytes) return bytes;
  if (bytes > SIZE_MAX - kHuge) return bytes;  // AllocateTable refuses it
  return bytes <= kPoolLargest ? ClassBytes(ClassOf(bytes)) : Rounded(bytes);
}

void* AllocateTable(size_t bytes) {
  if (!kMapTables || bytes < kPoolBytes) return ::operator new(bytes);
  if (bytes > SIZE_MAX - kHuge) throw std::bad_alloc();
  void* p = nullptr;
  if (bytes <= kPoolLargest) {
    p = ThePool().Take(ClassOf(bytes));
  } else {
    const size_t size = Rounded(bytes);
    p = TheCache().Take(size);
    if (p == nullptr) p = Map(size);
  }
  Metered(static_cast<int64_t>(TableFootprint(bytes)));
  return p;
}

void FreeTable(void* p, size_t bytes) noexcept {
  if (p == nullptr) return;
  if (!kMapTables || bytes < kPoolBytes) {
    ::operator delete(p);
    return;
  }
  if (bytes <= kPoolLargest) {
    ThePool().Give(p, ClassOf(bytes));
  } else if (!TheCache().Keep(p, Rounded(bytes))) {
    ::munmap(p, Rounded(bytes));
  }
  Metered(-static_cast<int64_t>(TableFootprint(bytes)));
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

size_t TablePoolBytes() { return ThePool().Bytes(); }

void TrimTableCache(size_t bytes) {
  ThePool().Trim();
  TheCache().Trim(bytes);
}

}  // namespace dot
