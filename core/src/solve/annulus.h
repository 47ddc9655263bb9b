// SPDX-License-Identifier: AGPL-3.0-or-later
// The minimal-cost annulus between two loops: a surface of genus 0 whose
// boundary is exactly loops A and B, over a set of candidate triangles with
// corners on the loops only. Exact over every such surface in the set, for
// per-triangle weights (DOT1) and bending between neighbours (DOT2).
//
// Structure used (see README, "Several loops"): every triangle of such a
// surface either has corners on both loops (a "cross" triangle) or lies in
// an ear hanging on a chord of one loop (LoopEars). The cross triangles form
// one cyclic strip: consecutive ones share an edge between the loops, and
// each has one side on a loop (a loop edge or an ear's chord) that advances
// along that loop. The strip is a cycle in the graph whose nodes are the
// edges between the loops and whose arcs are the cross triangles, winding
// once around both loops.
//
// The cycle is fixed by a canonical start: the run of A-sides at one vertex
// q of B that covers A's last edge (n_A - 1 -> 0) begins at node (a, q);
// from there a forward pass over the unrolled graph (A advancing from a to
// a + n_A, B from q to q + n_B) ends at (a, q) with a B-side. That start
// makes every edge between the loops appear once; every loop side count at
// least 3 per loop then makes every chord appear once, so each cycle found is
// a manifold surface (no edge used twice), and every valid surface is found
// exactly once. Candidates from one Delaunay tetrahedralization do not
// intersect, so neither does the result.
#ifndef DOT_CORE_SOLVE_ANNULUS_H_
#define DOT_CORE_SOLVE_ANNULUS_H_

#include <cstdint>
#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/status.h"
#include "solve/surface_costs.h"

namespace dot {

struct AnnulusSolution {
  double cost = 0;
  std::vector<Triangle> triangles;  // positions; loops run along them
  int64_t states = 0;               // DP states visited
  int64_t table_bytes = 0;
};

// Bytes SolveAnnulus's tables need at most for `candidates` triangles.
int64_t EstimateAnnulusBytes(int64_t candidates);

// `loop_a`, `loop_b`: positions in the direction each loop runs along the
// surface (the surface on its left); `candidates`: triangles over positions
// (any corner order). Only an annulus cheaper than `upper_bound` counts
// (kInf: any). kNoTriangulation when none exists among them;
// kResourceExhausted when its tables would exceed `memory_budget_bytes`.
Status SolveAnnulus(const std::vector<int32_t>& loop_a,
                    const std::vector<int32_t>& loop_b,
                    const std::vector<Triangle>& candidates,
                    const SurfaceCosts& costs, int64_t memory_budget_bytes,
                    double upper_bound, const Control& control,
                    AnnulusSolution* out);

}  // namespace dot

#endif  // DOT_CORE_SOLVE_ANNULUS_H_
