// SPDX-License-Identifier: AGPL-3.0-or-later
// Peak heap of one call: the bench binary replaces the global operator new
// and delete to count live bytes, so TetGen, CGAL and our tables are all
// measured the same way, in-process and without sampling.
#ifndef DOT_BENCH_HEAP_METER_H_
#define DOT_BENCH_HEAP_METER_H_

#include <cstdint>

namespace dot::bench {

// Starts a measurement: the peak restarts from the bytes live now.
void ResetHeapPeak();
// Highest live bytes since ResetHeapPeak, minus the bytes live at the reset.
int64_t HeapPeakBytes();

}  // namespace dot::bench

#endif  // DOT_BENCH_HEAP_METER_H_
