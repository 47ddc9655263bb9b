// SPDX-License-Identifier: AGPL-3.0-or-later
// What a face of the cycle search would cost as a patch: DOT's optimal
// squared-dihedral triangulation of its loop (after Zhuang et al. 2013, who
// weigh candidate cycles by their triangulation). A face the surface has
// spans its loop with little bending; one that twists across the surface (a
// junction's normal taken the wrong way round) bends more, or has no
// Delaunay triangulation at all.
#ifndef DOT_NETWORK_FACE_COST_H_
#define DOT_NETWORK_FACE_COST_H_

#include <map>
#include <vector>

#include "dot/control.h"
#include "dot/network.h"

namespace dot {

// The points of `face` that price it: each curve's first (the junctions),
// and between them an even share of at most FaceCosts::kMaxPoints.
std::vector<Vec3> PricedPoints(const NetworkGraph& graph,
                               const std::vector<CurveUse>& face);

// Faces priced once each (a face and its reverse cost the same).
class FaceCosts {
 public:
  // Triangulates under `control`'s cancel and deadline only (its progress
  // is the cycle search's, not each face's).
  FaceCosts(const NetworkGraph& graph, const Control& control) : graph_(graph) {
    control_.cancel = control.cancel;
    control_.deadline = control.deadline;
  }
  // The cost of `face` (curves in order, as a rotation system traces
  // them): the squared-dihedral cost of DOT's triangulation of its
  // PricedPoints; a face that runs a curve twice, or that DOT cannot
  // triangulate over its Delaunay triangles, costs kUnsurfaceable per
  // point.
  double Cost(const std::vector<CurveUse>& face);
  size_t priced() const { return cost_.size(); }

  static constexpr int kMaxPoints = 200;
  static constexpr double kUnsurfaceable = 10;

 private:
  const NetworkGraph& graph_;
  Control control_;
  std::map<std::vector<int32_t>, double> cost_;
};

}  // namespace dot

#endif  // DOT_NETWORK_FACE_COST_H_
