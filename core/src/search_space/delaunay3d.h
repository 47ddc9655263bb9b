// SPDX-License-Identifier: AGPL-3.0-or-later
// The 3D Delaunay search space of a non-planar polygon: the faces of its
// Delaunay tetrahedralization by the chosen backend, with optional edge
// protection: polygon edges on no Delaunay triangle are split at their
// midpoints and the tetrahedralization recomputed, until every polygon edge
// is Delaunay (paper, Lemma 4.3 and section 5.1).
#ifndef DOT_CORE_SEARCH_SPACE_DELAUNAY3D_H_
#define DOT_CORE_SEARCH_SPACE_DELAUNAY3D_H_

#include <vector>

#include "dot/control.h"
#include "dot/problem.h"
#include "dot/status.h"
#include "polygon/polygon_loop.h"

namespace dot {

// Fills `faces` (over loop positions) and the tetrahedra/face counts of
// `stats` with options.delaunay's backend; with options.protect_edges, may
// grow `loop` by at most options.max_inserted_vertices.
Status Delaunay3dFaces(const Options& options, const Control& control,
                       PolygonLoop* loop, std::vector<Triangle>* faces,
                       Stats* stats);

}  // namespace dot

#endif  // DOT_CORE_SEARCH_SPACE_DELAUNAY3D_H_
