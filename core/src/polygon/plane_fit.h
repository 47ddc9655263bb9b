// SPDX-License-Identifier: AGPL-3.0-or-later
// Least-squares plane and line of a point set, to decide whether a polygon
// is planar (then triangulated in 2D) or collinear (then rejected).
#ifndef DOT_CORE_POLYGON_PLANE_FIT_H_
#define DOT_CORE_POLYGON_PLANE_FIT_H_

#include <vector>

#include "dot/geometry.h"

namespace dot {

struct PlaneFit {
  Vec3 centroid;
  Vec3 normal;                    // unit normal of the least-squares plane
  Vec3 direction;                 // unit direction of the least-squares line
  double diagonal = 0;            // bounding-box diagonal
  double max_plane_distance = 0;  // largest distance of a point to the plane
  double max_line_distance = 0;   // largest distance of a point to the line
  int dominant_axis = 2;          // coordinate axis closest to the plane normal
};

PlaneFit FitPlane(const std::vector<Vec3>& points);

}  // namespace dot

#endif  // DOT_CORE_POLYGON_PLANE_FIT_H_
