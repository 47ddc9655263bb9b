// SPDX-License-Identifier: AGPL-3.0-or-later
// The last word on a junction's sign: what the faces cost as patches.
// Where junctions are far apart, the normals carried along long, bent
// curves can vote for the wrong sign (up to 9 % of the curves of a coarse
// cut mesh), and a face that twists across the surface bends more than the
// true ones (FaceCosts). Cost alone is no oracle either (it prefers a few
// wrong faces to true ones), so the votes stay in charge.
#ifndef DOT_NETWORK_SIGN_COST_H_
#define DOT_NETWORK_SIGN_COST_H_

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "dot/network.h"
#include "dot/status.h"
#include "network/face_cost.h"
#include "network/rotation.h"
#include "util/run_control.h"

namespace dot {

// A curve between two junctions: their rings, and whether the normal
// carried along it agrees with the other end's (+1) or not (-1) under the
// rings' signs before any flip (Rotation::sign all +1); 0: no vote.
struct CurveRings {
  int32_t from, to;
  int vote;
};

// How many more curve votes than it wins a flip may overrule.
inline constexpr int kVotesOverruled = 1;

// Flips a junction, both ends of a curve, or a subtree of the spanning
// forest (as ImproveSigns) when the faces it changes cost less as patches,
// no fewer or less simple (MoreSimple) and overruling at most
// kVotesOverruled more curve votes than it wins. Needs rot->sign. Stops,
// keeping what it has, when `costs` has no more points to price
// (FaceCosts::spent); a stopped ticker is the returned status.
Status ImproveByCost(Rotation* rot, const NetworkGraph& graph,
                     const std::vector<CurveRings>& curves,
                     const std::vector<int32_t>& order,
                     const std::vector<std::pair<size_t, size_t>>& subtrees,
                     FaceCosts* costs, RunTicker* ticker);

}  // namespace dot

#endif  // DOT_NETWORK_SIGN_COST_H_
