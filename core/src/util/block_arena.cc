// SPDX-License-Identifier: AGPL-3.0-or-later
#include "util/block_arena.h"

#include <algorithm>
#include <cassert>

#include "util/flat_vector.h"

namespace dot {
namespace {

constexpr size_t kLargestChunk = size_t{32} << 20;
constexpr size_t kAlign = alignof(std::max_align_t);

thread_local BlockArena* current = nullptr;

}  // namespace

BlockArena::BlockArena() : outer_(current) {
  if (kMapTables) current = this;
}

BlockArena::~BlockArena() {
  assert(current == this || !kMapTables);  // arenas nest on one stack
  if (current == this) current = outer_;
  for (const Chunk& c : chunks_) FreeTable(c.data, c.size);
}

BlockArena* BlockArena::Current() { return current; }

void* BlockArena::Allocate(size_t bytes) {
  if (bytes > kLargestChunk * 1024) throw std::bad_alloc();  // no wrapping
  bytes = (bytes + kAlign - 1) & ~(kAlign - 1);
  if (chunks_.empty() || chunks_.back().size - used_ < bytes) {
    // Until the arena holds 64 KiB, each block is a heap allocation of its
    // own size: a small tetrahedralization costs what it did without the
    // arena. From then on, chunks of 64 KiB and more, doubling up to
    // 32 MiB, all tables: on huge pages, the small ones sharing theirs.
    size_t size = bytes;
    if (bytes > kLargestChunk) {
      size = (bytes + kTableHugeBytes - 1) & ~(kTableHugeBytes - 1);
    } else if (reserved_ + bytes > kPoolBytes) {
      const size_t last = chunks_.empty() ? 0 : chunks_.back().size;
      size = kPoolBytes;  // a power of two: a pool class or whole 2 MiB
      while (size < std::min(2 * last, kLargestChunk) || size < bytes) {
        size *= 2;
      }
    }
    if (chunks_.size() == chunks_.capacity()) {
      chunks_.reserve(2 * chunks_.size() + 8);  // no throw once it is held
    }
    chunks_.push_back({static_cast<char*>(AllocateTable(size)), size});
    used_ = 0;
    reserved_ += size;
  }
  void* p = chunks_.back().data + used_;
  used_ += bytes;
  return p;
}

}  // namespace dot
