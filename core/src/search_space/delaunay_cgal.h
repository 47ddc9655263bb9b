// SPDX-License-Identifier: AGPL-3.0-or-later
// The CGAL 3D Delaunay backend: exact predicates, re-entrant, cancellable
// between insertions. Its output is the same whatever the insertion order or
// thread count: CGAL breaks cospherical ties by symbolic perturbation, so the
// tetrahedralization is unique.
#ifndef DOT_CORE_SEARCH_SPACE_DELAUNAY_CGAL_H_
#define DOT_CORE_SEARCH_SPACE_DELAUNAY_CGAL_H_

#include <cstdint>
#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/problem.h"
#include "dot/status.h"

namespace dot {

// Distinct faces (each sorted ascending, in no particular order) of the 3D
// Delaunay tetrahedralization of `points` (no duplicates, not all coplanar),
// and its number of finite tetrahedra. Polls `control` while inserting.
// Uses threads per options.parallel_delaunay_min_points and
// options.delaunay_threads; the faces do not depend on them.
Status CgalDelaunayFaces(const std::vector<Vec3>& points,
                         const Options& options, const Control& control,
                         std::vector<Triangle>* faces, int64_t* tetrahedra);

// The same with default Options.
inline Status CgalDelaunayFaces(const std::vector<Vec3>& points,
                                const Control& control,
                                std::vector<Triangle>* faces,
                                int64_t* tetrahedra) {
  return CgalDelaunayFaces(points, Options(), control, faces, tetrahedra);
}

// The dimension of the affine hull of `points` (0: one point, 1: a line,
// 2: a plane, 3: space), decided with exact predicates.
int AffineDimension(const std::vector<Vec3>& points);

}  // namespace dot

#endif  // DOT_CORE_SEARCH_SPACE_DELAUNAY_CGAL_H_
