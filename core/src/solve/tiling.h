// SPDX-License-Identifier: AGPL-3.0-or-later
// Tiling: reading the optimal triangulation back out of a solved dynamic
// program, top-down from the root edge. Shared by DOT1/GK1 and DOT2/GK2,
// which differ only in where they recorded their choices. An explicit stack,
// not recursion: a 100,000-vertex polygon must run on a 1 MiB stack.
#ifndef DOT_CORE_SOLVE_TILING_H_
#define DOT_CORE_SOLVE_TILING_H_

#include <cstdint>
#include <vector>

#include "solve/adjacency.h"

namespace dot {

// Replaces `triangles` with candidate `top` and everything chosen below it:
// under each short side s of a collected triangle u (0: [a, b], 1: [b, c])
// that is not a polygon edge, the triangle chosen_below(u, s).
template <typename ChosenBelow>
void CollectTiling(const Adjacency& adj, int32_t top, ChosenBelow chosen_below,
                   std::vector<int32_t>* triangles) {
  triangles->clear();
  std::vector<int32_t> stack = {top};
  while (!stack.empty()) {
    const int32_t u = stack.back();
    stack.pop_back();
    triangles->push_back(u);
    for (int s = 0; s < 2; ++s) {
      if (!adj.IsPolygonEdge(adj.tri_edges[3 * u + s])) {
        stack.push_back(chosen_below(u, s));
      }
    }
  }
}

}  // namespace dot

#endif  // DOT_CORE_SOLVE_TILING_H_
