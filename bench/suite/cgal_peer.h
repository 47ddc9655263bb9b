// SPDX-License-Identifier: AGPL-3.0-or-later
// The peer: CGAL 5.5's Polygon_mesh_processing::triangulate_hole_polyline,
// restricted to 3D Delaunay faces like DOT (use_delaunay_triangulation) and
// without its cubic all-triangles fallback, which would not finish at the
// sizes compared. It minimizes Liepa's (worst dihedral angle, area) weight.
#ifndef DOT_BENCH_CGAL_PEER_H_
#define DOT_BENCH_CGAL_PEER_H_

#include <vector>

#include "dot/geometry.h"

namespace dot::bench {

// Triangles over loop positions; empty when CGAL found no triangulation.
std::vector<Triangle> CgalFillHole(const std::vector<Vec3>& loop);

}  // namespace dot::bench

#endif  // DOT_BENCH_CGAL_PEER_H_
