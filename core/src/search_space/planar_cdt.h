// SPDX-License-Identifier: AGPL-3.0-or-later
// The search space of planar polygons: CGAL's 2D constrained Delaunay
// triangulation in the coordinate plane closest to the polygon's plane
// (paper, Lemma 4.4).
#ifndef DOT_CORE_SEARCH_SPACE_PLANAR_CDT_H_
#define DOT_CORE_SEARCH_SPACE_PLANAR_CDT_H_

#include <cstdint>
#include <vector>

#include "dot/geometry.h"
#include "dot/status.h"

namespace dot {

// Triangles (over loop positions, each sorted ascending, the list sorted) of
// the 2D constrained Delaunay triangulation of a planar polygon projected
// along `drop_axis` (its coordinates copied exactly, so the lifted triangles
// form a height field). Polygon edges run from position i to next[i] (one
// loop: i + 1 mod n; several loops: PolygonLoop::Successors). Every edge is
// a constraint. kInvalidArgument, naming two crossing edges, when the
// projected loops are not simple and disjoint.
Status PlanarCdtTriangles(const std::vector<Vec3>& loop,
                          const std::vector<int32_t>& next, int drop_axis,
                          std::vector<Triangle>* triangles);

}  // namespace dot

#endif  // DOT_CORE_SEARCH_SPACE_PLANAR_CDT_H_
