// SPDX-License-Identifier: AGPL-3.0-or-later
// The solve's tables: large ones mapped 2 MiB-aligned (for huge pages),
// counted by a meter, and kept for the next table when asked.
#include "util/flat_vector.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <vector>

#include "dot/table_memory.h"

namespace dot {
namespace {

std::atomic<int64_t> metered{0};
void Meter(int64_t delta) { metered += delta; }

TEST(TableAllocatorTest, LargeTablesAreAlignedForHugePagesAndMetered) {
  SetTableMeter(&Meter);
  metered = 0;
  {
    Table<int32_t> big(3 << 20);  // 12 MiB
    std::iota(big.begin(), big.end(), 0);
    EXPECT_EQ(big[(3 << 20) - 1], (3 << 20) - 1);
    EXPECT_EQ(big[12345], 12345);  // value-initialized, then written
    if (kMapTables) {
      EXPECT_EQ(reinterpret_cast<uintptr_t>(big.data()) % (2 << 20), 0u);
      EXPECT_EQ(metered.load(), int64_t{12} << 20);
    }
    Table<int32_t> small(1000);  // from operator new: not metered here
    EXPECT_EQ(small[999], 0);
    if (kMapTables) {
      EXPECT_EQ(metered.load(), int64_t{12} << 20);
    }
  }
  EXPECT_EQ(metered.load(), 0);
  SetTableMeter(nullptr);
}

// Tables of 64 KiB to 1 MiB share 2 MiB chunks, one size class each: a
// freed block serves the next table of its class; empty chunks stay until
// a trim returns them to the kernel (never to the cache). The meter counts
// the size classes, what the tables hold.
TEST(TableAllocatorTest, SmallTablesShareHugePageChunks) {
  if (!kMapTables) GTEST_SKIP() << "sanitizer build: tables on the heap";
  SetTableMeter(&Meter);
  metered = 0;
  SetTableCacheBytes(size_t{64} << 20);
  TrimTableCache(0);
  ASSERT_EQ(TablePoolBytes(), 0u);
  const auto chunk = [](const void* p) {
    return reinterpret_cast<uintptr_t>(p) & ~((uintptr_t{2} << 20) - 1);
  };
  {
    Table<char> a(100 << 10), b(104 << 10);  // both in the 108 KiB class
    Table<char> c(600 << 10);                // the 640 KiB class: its own chunk
    EXPECT_EQ(chunk(a.data()), chunk(b.data()));
    EXPECT_NE(chunk(a.data()), chunk(c.data()));
    EXPECT_EQ(std::abs(a.data() - b.data()), 108 << 10);
    EXPECT_EQ(metered.load(), (108 << 10) + (108 << 10) + (640 << 10));
    EXPECT_EQ(TablePoolBytes(), size_t{4} << 20);
    a.back() = 1;
    b.front() = 2;
    c.back() = 3;
    const char* a_block = a.data();
    a = Table<char>();         // freed: the chunk is still held by b
    Table<char> d(106 << 10);  // takes a's block back, value-initialized
    EXPECT_EQ(d.data(), a_block);
    EXPECT_EQ(d[(100 << 10) - 1], 0);  // where a.back() wrote 1
  }
  EXPECT_EQ(metered.load(), 0);
  EXPECT_EQ(TablePoolBytes(), size_t{4} << 20);  // both kept, empty
  EXPECT_EQ(TableCacheBytesHeld(), 0u);          // not the cache's
  TrimTableCache(size_t{64} << 20);              // to the kernel
  EXPECT_EQ(TablePoolBytes(), 0u);
  EXPECT_EQ(TableCacheBytesHeld(), 0u);
  SetTableCacheBytes(0);
  SetTableMeter(nullptr);
}

// Sixteen empty chunks stay, not more: the others go to the kernel, and a
// table taken from a kept chunk uses it again.
TEST(TableAllocatorTest, UpToSixteenEmptyChunksAreKept) {
  if (!kMapTables) GTEST_SKIP() << "sanitizer build: tables on the heap";
  SetTableCacheBytes(0);
  TrimTableCache(0);
  ASSERT_EQ(TablePoolBytes(), 0u);
  {
    std::vector<Table<char>> tables;  // 18 chunks of 32 blocks of 64 KiB
    for (int i = 0; i < 18 * 32; ++i) tables.emplace_back(64 << 10);
    EXPECT_EQ(TablePoolBytes(), size_t{36} << 20);
  }
  EXPECT_EQ(TablePoolBytes(), size_t{32} << 20);
  {
    Table<char> same(64 << 10);  // from a kept chunk: none mapped
    EXPECT_EQ(TablePoolBytes(), size_t{32} << 20);
    Table<char> other(80 << 10);  // a new class: a new chunk
    EXPECT_EQ(TablePoolBytes(), size_t{34} << 20);
  }
  EXPECT_EQ(TablePoolBytes(), size_t{32} << 20);  // sixteen kept: one went
  EXPECT_EQ(TableCacheBytesHeld(), 0u);
  TrimTableCache(0);
  EXPECT_EQ(TablePoolBytes(), 0u);
}

// With a cache, a freed table's pages serve the next one (and a smaller
// one takes the front of a larger block); without, none are kept.
TEST(TableAllocatorTest, FreedTablesAreKeptOnlyWhenAsked) {
  if (!kMapTables) GTEST_SKIP() << "sanitizer build: tables on the heap";
  SetTableCacheBytes(size_t{64} << 20);
  const void* first = nullptr;
  {
    FlatVector<double> a(size_t{4} << 20);  // 32 MiB
    a[0] = 1;
    first = a.data();
  }
  {
    FlatVector<double> b(size_t{2} << 20);  // 16 MiB: the same block
    EXPECT_EQ(static_cast<const void*>(b.data()), first);
    b[(size_t{2} << 20) - 1] = 2;
  }
  EXPECT_EQ(TableCacheBytesHeld(), size_t{16} << 20);  // the tail went
  SetTableCacheBytes(0);                               // returns what it held
  EXPECT_EQ(TableCacheBytesHeld(), 0u);
  {
    FlatVector<double> c(size_t{2} << 20);
    c[0] = 3;
    EXPECT_EQ(c[0], 3);
  }
  EXPECT_EQ(TableCacheBytesHeld(), 0u);
}

// Kept blocks too small for a table go back to the kernel before it is
// mapped, and a block far larger than asked is not cut down for it.
TEST(TableAllocatorTest, KeptBlocksThatCannotServeAreReturned) {
  if (!kMapTables) GTEST_SKIP() << "sanitizer build: tables on the heap";
  SetTableCacheBytes(size_t{256} << 20);
  { Table<char> small(size_t{4} << 20); }
  EXPECT_EQ(TableCacheBytesHeld(), size_t{4} << 20);
  { Table<char> larger(size_t{8} << 20); }  // a miss: the 4 MiB go back
  EXPECT_EQ(TableCacheBytesHeld(), size_t{8} << 20);
  { Table<char> big(size_t{100} << 20); }  // a miss: the 8 MiB go back
  EXPECT_EQ(TableCacheBytesHeld(), size_t{100} << 20);
  {
    Table<char> tiny(size_t{3} << 20);     // 100 MiB is too large to cut down
    EXPECT_EQ(TableCacheBytesHeld(), 0u);  // ... and a miss returns it
  }
  TrimTableCache(0);
  EXPECT_EQ(TableCacheBytesHeld(), 0u);
  SetTableCacheBytes(0);
}

}  // namespace
}  // namespace dot
