// SPDX-License-Identifier: AGPL-3.0-or-later
// What a face of the cycle search would cost as a patch: DOT's optimal
// squared-dihedral triangulation of its loop (after Zhuang et al. 2013, who
// weigh candidate cycles by their triangulation). A face the surface has
// spans its loop with little bending; one that twists across the surface (a
// junction's normal taken the wrong way round) bends more, or has no
// Delaunay triangulation at all.
#ifndef DOT_NETWORK_FACE_COST_H_
#define DOT_NETWORK_FACE_COST_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "dot/control.h"
#include "dot/network.h"

namespace dot {

// The points of `face` that price it, at most FaceCosts::kMaxPoints: each
// curve's first (the junctions) and an even share of the rest; a face of
// more than kMaxPoints / 2 curves, evenly spaced along the whole loop.
std::vector<Vec3> PricedPoints(const NetworkGraph& graph,
                               const std::vector<CurveUse>& face);

// Faces priced once each (a face and its reverse cost the same).
class FaceCosts {
 public:
  // Triangulates under `control`'s cancel and deadline only (its progress
  // is the cycle search's, not each face's), pricing at most `max_points`
  // points in all.
  FaceCosts(const NetworkGraph& graph, const Control& control,
            int64_t max_points);
  // The squared-dihedral cost of DOT's triangulation of the face's
  // PricedPoints (taken the same way round whichever way it runs); a
  // pinched face (one that runs a curve twice or passes a junction twice:
  // no patch's rim does), or one DOT cannot triangulate over its Delaunay
  // triangles, costs kUnsurfaceable per point. Nothing once the caller
  // stops the run or the points to price are spent.
  std::optional<double> Cost(const std::vector<CurveUse>& face);
  bool spent() const { return priced_points_ > max_points_; }
  size_t priced() const { return cost_.size(); }

  static constexpr int kMaxPoints = 200;
  static constexpr double kUnsurfaceable = 10;

 private:
  const NetworkGraph& graph_;
  Control control_;
  int64_t max_points_;
  int64_t priced_points_ = 0;
  std::map<std::vector<int32_t>, double> cost_;
};

}  // namespace dot

#endif  // DOT_NETWORK_FACE_COST_H_
