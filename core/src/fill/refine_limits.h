// SPDX-License-Identifier: AGPL-3.0-or-later
// How far Liepa refinement (CGAL's refine(), which has no way to stop) may
// go: the most vertices a patch may gain, and the output iterator that
// counts them as CGAL adds them and stops it, past the cap or when the run
// must stop. Shared by FillHoles' patches and curve networks' (network/).
#ifndef DOT_CORE_FILL_REFINE_LIMITS_H_
#define DOT_CORE_FILL_REFINE_LIMITS_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dot/status.h"
#include "util/run_control.h"

namespace dot {

// What refinement and fairing take per new vertex, about.
inline constexpr int64_t kBytesPerRefinedVertex = 4096;

// The most vertices refinement may add to a patch of `rim` boundary
// vertices: Liepa's default density gives about 0.1 rim^2 in a round hole,
// so this leaves room for densities up to ~4x the default, within
// `memory_budget_bytes` (but never below `floor`).
inline size_t RefinedVertexCap(size_t rim, int64_t memory_budget_bytes,
                               int64_t floor = 1000) {
  const size_t by_rim = 2 * rim * rim + 1000;
  const size_t by_budget = static_cast<size_t>(
      std::max<int64_t>(floor, memory_budget_bytes / kBytesPerRefinedVertex));
  return std::min(by_rim, by_budget);
}

// Thrown from inside CGAL's refinement by CountingVertexOut; caught around
// the call.
struct StopRefining {
  Status status;  // cancel or deadline; OK when the vertex cap was reached
};

// Counts the vertices refinement adds into `out`, and stops it when there
// are more than `cap` or `ticker` says stop.
template <class VertexIndex>
struct CountingVertexOut {
  std::vector<VertexIndex>* out;
  size_t cap;
  RunTicker* ticker;

  CountingVertexOut& operator*() { return *this; }
  CountingVertexOut& operator++() { return *this; }
  CountingVertexOut operator++(int) { return *this; }
  CountingVertexOut& operator=(VertexIndex v) {
    out->push_back(v);
    if (out->size() > cap) throw StopRefining{OkStatus()};
    if ((out->size() & 63) == 0 && !ticker->Poll()) {
      throw StopRefining{ticker->status()};
    }
    return *this;
  }
};

}  // namespace dot

#endif  // DOT_CORE_FILL_REFINE_LIMITS_H_
