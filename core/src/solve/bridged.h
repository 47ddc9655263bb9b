// SPDX-License-Identifier: AGPL-3.0-or-later
// Three or more loops into one surface, approximately: join the loops by
// bridges first, then triangulate the one polygon they make exactly.
//
// A surface of genus 0 bounded by k loops, cut along k - 1 of its edges
// that join the loops as a tree ("bridges"), is a disk whose border walks
// every loop in its direction and every bridge both ways. Given the bridges,
// the optimal such disk over the candidate triangles is the single-loop DP
// (DOT1 or DOT2) over that weakly simple polygon of n + 2(k - 1) positions.
// The bridges are chosen, not searched: short candidate edges between
// loops (Kruskal over loops, each vertex ending at most one bridge), the
// shortest tree first and then trees that swap out one bridge at a time,
// keeping the cheapest surface. So the answer is the optimum for its
// bridges, not over every surface: reported as an approximation. The
// bending across a bridge is not priced by the DP (it is a border of the
// polygon) but is in the cost the caller evaluates. Candidate triangles
// never intersect (Delaunay faces or a planar CDT), and a result whose
// edges are not manifold (one edge reached from both copies of a bridge
// end) is refused and re-solved without the chord that caused it.
#ifndef DOT_CORE_SOLVE_BRIDGED_H_
#define DOT_CORE_SOLVE_BRIDGED_H_

#include <cstdint>
#include <utility>
#include <vector>

#include "dot/control.h"
#include "dot/status.h"
#include "solve/surface_costs.h"

namespace dot {

struct BridgedSolution {
  double cost = 0;  // the surface's, every term (bridges' bending too)
  std::vector<Triangle> triangles;  // loop positions; loops run along them
  std::vector<std::pair<int32_t, int32_t>> bridges;  // loop positions
  int32_t trees_tried = 0;
  int64_t states = 0;
  int64_t table_bytes = 0;
};

// `loops`: positions of each loop in the direction it runs along the
// surface; `candidates`: triangles over positions (any corner order) that
// meet only at shared corners and edges. kNoTriangulation when no tree of
// bridges tried gives a surface.
Status SolveBridged(const std::vector<std::vector<int32_t>>& loops,
                    const std::vector<Triangle>& candidates,
                    const SurfaceCosts& costs, int64_t memory_budget,
                    const Control& control, BridgedSolution* out);

}  // namespace dot

#endif  // DOT_CORE_SOLVE_BRIDGED_H_
