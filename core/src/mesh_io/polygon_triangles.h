// SPDX-License-Identifier: AGPL-3.0-or-later
// One polygon of a soup into triangles, as the readers and the repair do it.
#ifndef DOT_CORE_MESH_IO_POLYGON_TRIANGLES_H_
#define DOT_CORE_MESH_IO_POLYGON_TRIANGLES_H_

#include <vector>

#include "dot/control.h"
#include "dot/mesh.h"
#include "dot/status.h"

namespace dot {

// Appends the triangles of polygon `f` (ids into `vertices`) to `out`:
// DOT's minimal-area triangulation of its corners (planar polygons go
// through the 2D constrained Delaunay triangulation), or a fan when DOT
// refuses it (e.g. a polygon that repeats a corner). A triangle is itself.
// Fails only when `control` stops the run.
Status TriangulatePolygon(const std::vector<Vec3>& vertices, FaceView f,
                          const Control& control, std::vector<Triangle>* out);

}  // namespace dot

#endif  // DOT_CORE_MESH_IO_POLYGON_TRIANGLES_H_
