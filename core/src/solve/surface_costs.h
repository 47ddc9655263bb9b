// SPDX-License-Identifier: AGPL-3.0-or-later
// How a triangle of a surface over loop positions is priced: the weighted
// per-triangle metrics of the oriented triangle, the bending between two
// neighbours, and the bending against the surrounding face across a loop
// edge. Shared by the solvers of several loops (ears, annulus).
#ifndef DOT_CORE_SOLVE_SURFACE_COSTS_H_
#define DOT_CORE_SOLVE_SURFACE_COSTS_H_

#include <cstdint>
#include <vector>

#include "dot/geometry.h"
#include "dot/metrics.h"
#include "solve/solvers.h"

namespace dot {

struct SurfaceCosts {
  std::vector<Vec3> points;        // per position (work coordinates)
  std::vector<Vec3> normals;       // per position, or empty
  std::vector<Vec3> edge_normals;  // per position: face across edge p->next
  MetricWeights weights;           // per-triangle metrics
  BendingWeights bending;          // zero: DOT1

  bool bi() const {
    return bending.dihedral != 0 || bending.squared_dihedral != 0;
  }
  double Weight(const Triangle& oriented) const {
    return WeightedTriangleCost(weights, points, normals, oriented);
  }
  Vec3 Normal(const Triangle& oriented) const {
    return UnitNormal(points, oriented);
  }
  double Bend(const Vec3& a, const Vec3& b) const {
    if (!bi()) return 0;
    const double theta = BendingAngle(a, b);
    return bending.dihedral * theta + bending.squared_dihedral * theta * theta;
  }
  // Against the surface face across the loop edge leaving `pos`, if any.
  double BoundaryBend(int32_t pos, const Vec3& n) const {
    if (!bi() || edge_normals.empty() || Norm(edge_normals[pos]) == 0) {
      return 0;
    }
    return Bend(edge_normals[pos], n);
  }
  // The least Bend() can be (a lower bound for pruning).
  double MinBend() const { return MinBending(bending); }
  // Whether no term can be negative, so a partial sum bounds the total.
  bool NonNegative() const {
    for (double w : weights.v) {
      if (w < 0) return false;
    }
    return MinBend() >= 0;
  }
};

}  // namespace dot

#endif  // DOT_CORE_SOLVE_SURFACE_COSTS_H_
