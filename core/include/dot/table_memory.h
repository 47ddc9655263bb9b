// SPDX-License-Identifier: AGPL-3.0-or-later
// The memory of a solve's large tables (adjacency, DP entries, the edge
// index): mapped on transparent huge pages (core/src/util/flat_vector.h),
// and, when a process asks, kept once freed for the next solves.
#ifndef DOT_TABLE_MEMORY_H_
#define DOT_TABLE_MEMORY_H_

#include <cstddef>

namespace dot {

// Keeps up to `bytes` of freed tables for the next solves (default 0: all
// are returned to the kernel at once, but for up to 16 empty 2 MiB chunks
// of the tables under 1 MiB, 32 MiB, kept as malloc keeps its heap), so a
// process that solves again and again reuses pages already faulted in. A table the kept blocks cannot
// serve first returns as many of them. Thread-safe; lowering the limit
// returns the excess at once. dot-server keeps half of --malloc-keep-mb,
// dotctl 256 MiB.
void SetTableCacheBytes(size_t bytes);
// The freed table bytes kept now.
size_t TableCacheBytesHeld();
// Returns kept tables to the kernel, oldest first, until at most `bytes`
// are kept (the limit is unchanged); the small tables' empty chunks first.
void TrimTableCache(size_t bytes);

}  // namespace dot

#endif  // DOT_TABLE_MEMORY_H_
