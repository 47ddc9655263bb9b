// SPDX-License-Identifier: AGPL-3.0-or-later
// BlockArena hands out aligned, disjoint blocks from growing chunks while it
// is current on its thread; ArenaAllocator uses the arena current when it
// was made, and the heap otherwise.
#include "util/block_arena.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <list>
#include <thread>
#include <utility>
#include <vector>

#include "util/flat_vector.h"

namespace dot {
namespace {

TEST(BlockArenaTest, IsCurrentWhileAliveAndNests) {
  EXPECT_EQ(BlockArena::Current(), nullptr);
  {
    BlockArena outer;
    if (!kMapTables) GTEST_SKIP() << "sanitizer builds keep blocks on the heap";
    EXPECT_EQ(BlockArena::Current(), &outer);
    {
      BlockArena inner;
      EXPECT_EQ(BlockArena::Current(), &inner);
      std::thread([] { EXPECT_EQ(BlockArena::Current(), nullptr); }).join();
    }
    EXPECT_EQ(BlockArena::Current(), &outer);
  }
  EXPECT_EQ(BlockArena::Current(), nullptr);
}

TEST(BlockArenaTest, BlocksAreAlignedDisjointAndWritable) {
  BlockArena arena;
  std::vector<std::pair<char*, size_t>> blocks;
  // Sizes like a Compact_container's growing blocks, and one larger than
  // any chunk so far.
  for (size_t size = 24; size < (size_t{3} << 20); size = size * 3 / 2 + 40) {
    blocks.emplace_back(static_cast<char*>(arena.Allocate(size)), size);
  }
  blocks.emplace_back(static_cast<char*>(arena.Allocate(size_t{40} << 20)),
                      size_t{40} << 20);
  for (const auto& [p, size] : blocks) {
    EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % alignof(std::max_align_t), 0u);
    std::memset(p, 0xab, size);
  }
  std::sort(blocks.begin(), blocks.end());
  for (size_t i = 1; i < blocks.size(); ++i) {
    EXPECT_LE(blocks[i - 1].first + blocks[i - 1].second, blocks[i].first);
  }
  size_t total = 0;
  for (const auto& b : blocks) total += b.second;
  EXPECT_GE(arena.Reserved(), total);
  // Chunks double: less than twice what was asked for, plus the first.
  EXPECT_LT(arena.Reserved(), 2 * total + (size_t{2} << 20));
}

TEST(ArenaAllocatorTest, UsesTheArenaCurrentWhenItWasMade) {
  if (!kMapTables) GTEST_SKIP() << "sanitizer builds keep blocks on the heap";
  const ArenaAllocator<int> heap;
  EXPECT_EQ(heap.arena, nullptr);
  BlockArena arena;
  const ArenaAllocator<int> in_arena;
  EXPECT_EQ(in_arena.arena, BlockArena::Current());
  EXPECT_FALSE(heap == in_arena);
  // Rebinding keeps the arena (CGAL rebinds to its element types).
  EXPECT_EQ(ArenaAllocator<double>(in_arena).arena, in_arena.arena);
  // A node container made before the arena frees into the heap after it.
  std::list<int, ArenaAllocator<int>> before(heap);
  std::list<int, ArenaAllocator<int>> during;
  for (int i = 0; i < 1000; ++i) {
    before.push_back(i);
    during.push_back(i);
  }
  before.clear();
  during.clear();
  EXPECT_TRUE(before.empty() && during.empty());
}

}  // namespace
}  // namespace dot
