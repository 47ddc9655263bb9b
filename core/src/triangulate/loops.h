// SPDX-License-Identifier: AGPL-3.0-or-later
// Triangulate's path for several loops (Problem::loop_sizes): the search
// space over all their vertices, then the surface solver for that many loops.
#ifndef DOT_CORE_TRIANGULATE_LOOPS_H_
#define DOT_CORE_TRIANGULATE_LOOPS_H_

#include "dot/control.h"
#include "dot/problem.h"
#include "dot/status.h"
#include "polygon/plane_fit.h"
#include "polygon/polygon_loop.h"

namespace dot {

// `loop` holds the loops in work coordinates (sizes set); edge protection
// may grow it, and a loop the solver reversed is reversed in it. Fills the
// result's triangles (vertex ids), solver, space, reversed loops and stats.
Status SolveLoops(const PlaneFit& fit, bool planar,
                  const MetricWeights& weights, const Problem& problem,
                  const Options& options, const Control& control,
                  PolygonLoop* loop, Result* r);

}  // namespace dot

#endif  // DOT_CORE_TRIANGULATE_LOOPS_H_
