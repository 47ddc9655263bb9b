// SPDX-License-Identifier: AGPL-3.0-or-later
#ifndef DOT_CORE_NETWORK_ISLANDS_H_
#define DOT_CORE_NETWORK_ISLANDS_H_

#include <string>
#include <vector>

#include "dot/network.h"
#include "util/run_control.h"

namespace dot {

// Lone loops into islands. A lone loop (a cycle alone in its part of the
// network: a closed curve drawn on its own) lies in a face of another part
// when, seen along that face's normal, every point of it is inside the
// face's outer loop and near the face's plane (within the face's own
// distance from its plane plus a quarter of its radius). It becomes an
// island of the smallest such face (by vector area): a second loop of that
// face's patch, run against it (the multi-loop solver joins them). kInset
// keeps the loop's own patch, turned to face as that face does (a curve
// drawn on a face: the surface stays closed); kHole drops it (a hole in
// the face: a loop inside that hole is on no face); kOff changes nothing.
// Nested loops pair inward. Each pairing is noted. False when the ticker
// says stop.
bool PairIslands(const NetworkGraph& graph, NetworkIslands mode,
                 std::vector<NetworkCycle>* cycles,
                 std::vector<std::string>* notes, RunTicker* ticker);

}  // namespace dot

#endif  // DOT_CORE_NETWORK_ISLANDS_H_
