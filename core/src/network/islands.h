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
// face's outer loop and no edge of it crosses that loop, the two face
// within 45 degrees of each other, and the loop is no farther from the
// face's plane than the face's own loop is, plus its own radius and plus a
// quarter of the face's (a circle drawn on a domed face, not one floating
// above a lid). It becomes an island of the nearest such face (then the
// smallest, by vector area): a second loop of that face's patch, run
// against it (the multi-loop solver joins them). kInset keeps the loop's
// own patch, turned to face as that face does (a curve drawn on a face:
// the surface stays closed); kHole drops it (a hole in the face: a loop
// inside that hole is on no face); kOff changes nothing. Nested loops pair
// inward; a face that runs a curve twice (a seam) holds none. Each pairing
// is noted. False when the ticker says stop.
bool PairIslands(const NetworkGraph& graph, NetworkIslands mode,
                 std::vector<NetworkCycle>* cycles,
                 std::vector<std::string>* notes, RunTicker* ticker);

}  // namespace dot

#endif  // DOT_CORE_NETWORK_ISLANDS_H_
