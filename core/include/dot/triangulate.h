// SPDX-License-Identifier: AGPL-3.0-or-later
// The library's one call: Triangulate(problem, options, control) returns the
// minimal-cost triangulation of a closed 3D polygon over a search space.
//
// Search spaces (paper: Zou, Ju, Carr, "Delaunay-restricted optimal
// triangulation of 3D polygons"):
//  - kDelaunay: triangles of the 3D Delaunay tetrahedralization of the
//    vertices (CGAL or TetGen, exact predicates on the input coordinates),
//    solved by DOT1 / DOT2. Output
//    is free of self-intersections by construction. Planar and nearly planar
//    polygons are triangulated instead over the 2D constrained Delaunay
//    triangulation in their dominant coordinate plane (CGAL), so the output is
//    a height field over that plane.
//  - kAll: every non-degenerate triangle on the vertices (GK1 / GK2): the
//    unrestricted optimum, which may self-intersect; the result counts the
//    intersecting pairs. Memory grows as n^3: for small n only.
//  - kDelaunayFirst: every triangle, the Delaunay ones first (one loop):
//    the cubic interval program of Gilbert and Klincsek (O(n^2) memory, up
//    to Options::delaunay_first_max_vertices), minimizing first how many
//    triangles are not Delaunay, then the cost (bending priced against each
//    sub-chain's own optimum: exact for per-triangle weights, an
//    approximation with bending weights, Solver::kGk2Greedy). May
//    self-intersect only where it leaves the Delaunay triangles; the result
//    counts the intersecting pairs. For polygons with no Delaunay
//    triangulation that are too large for kAll.
//  - kAuto: kDelaunay, then kAll when no Delaunay triangulation exists and
//    n <= Options::all_space_max_vertices, accepted only when its optimum is
//    intersection-free (otherwise kNoTriangulation, saying so).
// DOT1/GK1 run when only per-triangle weights are non-zero, DOT2/GK2 when a
// bi-triangle weight is. Both are exact minimizers; ties break
// deterministically.
//
// Thread safety: TetGen keeps file-scope state, so concurrent calls that reach
// the TetGen backend are serialized (it holds a mutex) unless a caller runs it
// in separate processes (Control::tetrahedralize). The CGAL backend and
// everything else is re-entrant.
#ifndef DOT_TRIANGULATE_H_
#define DOT_TRIANGULATE_H_

#include "dot/control.h"
#include "dot/problem.h"

namespace dot {

// Checks the problem, then solves it. Never throws; every failure is in
// Result::status with a message naming the offending input.
Result Triangulate(const Problem& problem, const Options& options = {},
                   const Control& control = {});

}  // namespace dot

#endif  // DOT_TRIANGULATE_H_
