// SPDX-License-Identifier: AGPL-3.0-or-later
#ifndef DOT_CORE_NETWORK_WALLS_H_
#define DOT_CORE_NETWORK_WALLS_H_

#include <string>
#include <vector>

#include "dot/network.h"
#include "util/run_control.h"

namespace dot {

// Walls (CycleOptions::walls): patches that make a third (or further)
// patch on their curves, as a partition inside a box. A rotation system
// gives every curve two faces, so the faces found leave a wall out; its
// trace is left at the junctions:
// at each of its corners the wall turns between two curves that no face
// turns between (a corner the faces leave unused, which only junctions of
// four curves or more have). A wall is a cycle of at most 8 curves, its
// junctions distinct, that turns only at unused corners, lies flat (every
// point within 5 % of its radius of its plane) and holds no other point of
// the network, vertex or edge midpoint (else it would be the outline of
// faces found, two coplanar squares side by side). Walls are taken
// smallest first, each unused corner by one wall at most, appended to
// `cycles` and noted. The search is bounded (200,000 steps; a note says
// when it stopped early). False when the ticker says stop.
bool FindWalls(const NetworkGraph& graph, std::vector<NetworkCycle>* cycles,
               std::vector<std::string>* notes, RunTicker* ticker);

}  // namespace dot

#endif  // DOT_CORE_NETWORK_WALLS_H_
