// SPDX-License-Identifier: AGPL-3.0-or-later
#include "util/block_arena.h"

#include <algorithm>

#include "util/flat_vector.h"

namespace dot {
namespace {

constexpr size_t kFirstChunk = size_t{64} << 10;
constexpr size_t kLargestChunk = size_t{32} << 20;
constexpr size_t kAlign = alignof(std::max_align_t);

thread_local BlockArena* current = nullptr;

}  // namespace

BlockArena::BlockArena() : outer_(current) {
  if (kMapTables) current = this;
}

BlockArena::~BlockArena() {
  if (current == this) current = outer_;
  for (const Chunk& c : chunks_) FreeTable(c.data, c.size);
}

BlockArena* BlockArena::Current() { return current; }

void* BlockArena::Allocate(size_t bytes) {
  bytes = (bytes + kAlign - 1) & ~(kAlign - 1);
  if (chunks_.empty() || chunks_.back().size - used_ < bytes) {
    // 64 KiB, then 2 MiB (a whole huge page), then doubling.
    size_t size = chunks_.empty() ? kFirstChunk
                  : chunks_.back().size < kTableMapBytes
                      ? kTableMapBytes
                      : std::min(2 * chunks_.back().size, kLargestChunk);
    if (size < bytes)
      size = (bytes + kTableMapBytes - 1) & ~(kTableMapBytes - 1);
    chunks_.reserve(chunks_.size() + 1);  // no throw after the table is held
    chunks_.push_back({static_cast<char*>(AllocateTable(size)), size});
    used_ = 0;
    reserved_ += size;
  }
  void* p = chunks_.back().data + used_;
  used_ += bytes;
  return p;
}

}  // namespace dot
