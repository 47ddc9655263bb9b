// SPDX-License-Identifier: AGPL-3.0-or-later
// The memory of a solve's large tables (candidate triangles, adjacency, DP
// entries): mapped on transparent huge pages (core/src/util/flat_vector.h),
// and, when a process asks, kept once freed for the next solves.
#ifndef DOT_TABLE_MEMORY_H_
#define DOT_TABLE_MEMORY_H_

#include <cstddef>

namespace dot {

// Keeps up to `bytes` of freed tables for the next solves (default 0: all
// are returned to the kernel at once), so a process that solves again and
// again reuses pages already faulted in. Thread-safe; lowering it returns
// the excess at once. dot-server sets it from --malloc-keep-mb, dotctl
// keeps 256 MiB.
void SetTableCacheBytes(size_t bytes);

}  // namespace dot

#endif  // DOT_TABLE_MEMORY_H_
