// SPDX-License-Identifier: AGPL-3.0-or-later
// The 3D Delaunay search space, with optional edge protection: polygon edges
// on no Delaunay triangle are split at their midpoints and the
// tetrahedralization recomputed, until every polygon edge is Delaunay
// (paper, Lemma 4.3 and section 5.1).
#ifndef DOT_CORE_EDGE_PROTECTION_H_
#define DOT_CORE_EDGE_PROTECTION_H_

#include <vector>

#include "dot/status.h"
#include "dot/triangulate.h"
#include "polygon_loop.h"

namespace dot {

// Fills `faces` (over loop positions) and the tetrahedra/face counts of
// `stats`; with `protect`, may grow `loop`.
Status Delaunay3dFaces(bool protect, int max_inserted, const Control& control,
                       PolygonLoop* loop, std::vector<Triangle>* faces,
                       Stats* stats);

}  // namespace dot

#endif  // DOT_CORE_EDGE_PROTECTION_H_
