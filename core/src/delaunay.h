// SPDX-License-Identifier: AGPL-3.0-or-later
// Candidate triangle sets (search spaces) over polygon positions 0..n-1,
// each triangle sorted ascending.
#ifndef DOT_CORE_DELAUNAY_H_
#define DOT_CORE_DELAUNAY_H_

#include <array>
#include <cstdint>
#include <vector>

#include "dot/geometry.h"
#include "dot/status.h"
#include "dot/triangulate.h"

namespace dot {

// TetgenTetrahedralize is declared in dot/triangulate.h (public: the
// server's helper processes call it).

// Distinct faces (sorted ascending) of the 3D Delaunay tetrahedralization of
// `points` (no duplicates, not all coplanar) by CGAL, and its number of
// finite tetrahedra. Polls `control` while inserting.
Status CgalDelaunayFaces(const std::vector<Vec3>& points,
                         const Control& control, std::vector<Triangle>* faces,
                         int64_t* tetrahedra);

// Distinct faces of a tetrahedralization, each sorted ascending, found
// through the neighbour lists in one linear pass. kInternal when the
// neighbour lists are inconsistent.
Status FacesOfTetrahedra(const Tetrahedralization& t,
                         std::vector<Triangle>* faces);

// Triangles of the 2D constrained Delaunay triangulation of a planar polygon
// projected along `drop_axis` (its coordinates copied exactly, so the lifted
// triangles form a height field). kInvalidArgument, naming two crossing
// edges, when the projection is not a simple polygon.
Status PlanarCdtTriangles(const std::vector<Vec3>& loop, int drop_axis,
                          std::vector<Triangle>* triangles);

// Every non-degenerate triangle on n positions (the GK search space).
Status AllTriangles(const std::vector<Vec3>& loop, const Control& control,
                    std::vector<Triangle>* triangles);

}  // namespace dot

#endif  // DOT_CORE_DELAUNAY_H_
