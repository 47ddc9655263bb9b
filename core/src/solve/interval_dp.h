// SPDX-License-Identifier: AGPL-3.0-or-later
// Every triangle of one loop, Delaunay ones first: the interval dynamic
// program of Gilbert and Klincsek (cost[i][k] over the chain i..k, O(n^3)
// time, O(n^2) memory, no table of candidate triangles: what CGAL's cubic
// search does), minimizing first how many triangles are not in a preferred
// set (the faces of the loop's Delaunay tetrahedralization, which never
// cross one another), then the weighted cost.
//
// Per-triangle metrics are exact. Bending terms (dihedral, squared
// dihedral) are priced against the triangle each sub-chain's own optimum
// puts on the shared edge, as CGAL prices its dihedral angles: the DP stays
// cubic, the cost it reports is the true cost of the triangulation it
// returns, but with bending weights that triangulation is not always the
// optimum (GK2 is O(n^4)). Without bending weights it is the exact optimum
// of the lexicographic objective.
//
// Nothing here prevents two non-preferred triangles, or one and a
// preferred one, from crossing: callers validate the result.
#ifndef DOT_CORE_SOLVE_INTERVAL_DP_H_
#define DOT_CORE_SOLVE_INTERVAL_DP_H_

#include <cstdint>
#include <utility>
#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/metrics.h"
#include "dot/status.h"

namespace dot {

struct IntervalDpInput {
  std::vector<Vec3> points;         // the loop, closed from last to first
  std::vector<Vec3> normals;        // per vertex; only for kNormalDeviation
  std::vector<Vec3> edge_normals;   // as Problem::edge_face_normals; unit
  MetricWeights weights;            // work units
  std::vector<Triangle> preferred;  // over positions, any vertex order
  std::vector<std::pair<int32_t, int32_t>> forbidden;  // chords
};

struct IntervalDpSolution {
  std::vector<Triangle> triangles;  // positions, oriented like the loop
  double cost = 0;                  // weighted, bending included
  int32_t not_preferred = 0;        // triangles outside `preferred`
  int64_t table_bytes = 0;
};

// Bytes the tables take for a loop of n vertices, with or without bending
// weights (checked against a budget before allocating).
int64_t IntervalDpBytes(int64_t n, bool bending);

// kNoTriangulation when every triangulation uses a forbidden chord or a
// degenerate triangle; kCancelled / kDeadlineExceeded per `control`.
Status SolveIntervalDp(const IntervalDpInput& in, const Control& control,
                       IntervalDpSolution* out);

}  // namespace dot

#endif  // DOT_CORE_SOLVE_INTERVAL_DP_H_
