// SPDX-License-Identifier: AGPL-3.0-or-later
// The memory of a solve's large tables (adjacency, DP entries, the edge
// index): mapped on transparent huge pages (core/src/util/flat_vector.h),
// and, when a process asks, kept once freed for the next solves.
#ifndef DOT_TABLE_MEMORY_H_
#define DOT_TABLE_MEMORY_H_

#include <cstddef>

namespace dot {

// Keeps up to `bytes` of freed tables of 2 MiB or more for the next
// solves (default 0: all are returned to the kernel at once), so a process
// that solves again and again reuses pages already faulted in. A table the
// kept blocks cannot serve first returns as many of them. Thread-safe;
// lowering the limit returns the excess at once. dot-server keeps half of
// --malloc-keep-mb, dotctl 256 MiB. Smaller tables share 2 MiB chunks,
// of which up to 16 (32 MiB) stay when empty whatever this limit, as
// malloc keeps its heap.
void SetTableCacheBytes(size_t bytes);
// The freed table bytes kept now (not counting the small tables' chunks).
size_t TableCacheBytesHeld();
// Returns every empty chunk of the small tables to the kernel, then kept
// tables, oldest first, until at most `bytes` are kept (the limit is
// unchanged).
void TrimTableCache(size_t bytes);

}  // namespace dot

#endif  // DOT_TABLE_MEMORY_H_
