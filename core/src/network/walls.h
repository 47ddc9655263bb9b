// SPDX-License-Identifier: AGPL-3.0-or-later
#ifndef DOT_CORE_NETWORK_WALLS_H_
#define DOT_CORE_NETWORK_WALLS_H_

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "dot/network.h"
#include "util/run_control.h"

namespace dot {

// The corner between darts a and b at their junction (dart 2c + end),
// the smaller first.
std::pair<int32_t, int32_t> Corner(int32_t a, int32_t b);

// Walls (CycleOptions::walls): patches that make a third (or further)
// patch on their curves, as a partition inside a box. A rotation system
// gives every curve two faces, so the faces found leave a wall out; its
// trace is left at the junctions: at each of its corners the wall turns
// between two curves that are not neighbours in the rotation (`used`: the
// neighbouring dart pairs, dart 2c + end), which only junctions of four
// curves or more have. A wall is a cycle of at most 8 curves (no closed
// curve), its junctions distinct, that turns only at such corners, lies
// flat (every point within 5 % of its radius of its plane) and holds no
// other point of the network: no vertex or edge midpoint of another curve
// inside it (else it would be the outline of faces found, a face's rim
// around its diagonals), no edge through it or across its rim. Walls are
// taken smallest first, each corner in one wall at most, and a wall that
// meets a taken one at a junction without a curve in common there (they
// cross) is left out. Walls are appended to `cycles` (NetworkCycle::wall)
// and noted. The search takes at most 20,000 steps from each junction (a
// note says when one ran out). False when the ticker says stop.
bool FindWalls(const NetworkGraph& graph,
               const std::set<std::pair<int32_t, int32_t>>& used,
               std::vector<NetworkCycle>* cycles,
               std::vector<std::string>* notes, RunTicker* ticker);

}  // namespace dot

#endif  // DOT_CORE_NETWORK_WALLS_H_
