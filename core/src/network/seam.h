// SPDX-License-Identifier: AGPL-3.0-or-later
#ifndef DOT_CORE_NETWORK_SEAM_H_
#define DOT_CORE_NETWORK_SEAM_H_

#include <string>
#include <vector>

#include "dot/network.h"

namespace dot {

// A loop that runs one path of curves both ways (a tube's seam, or a curve
// joining a hole to its rim): with the path taken out it is two closed
// walks, joined here by a new straight path between a vertex of each half
// way round from the seam, its points spaced as the loop's edges. Each
// piece is a simple loop of graph ids and, from graph.vertices.size(), the
// new path's points (new_vertices); the two pieces run the new path
// opposite ways. False (`why` says why) when the loop is not of that shape
// or a piece is not simple.
struct SeamSplit {
  std::vector<std::vector<int32_t>> pieces;
  std::vector<Vec3> new_vertices;
  std::vector<int32_t> seam;   // graph ids along the seam path
  int32_t from = -1, to = -1;  // graph ids the new path joins
};
bool RunsACurveTwice(const std::vector<CurveUse>& loop);
// Whether the curves a loop runs twice are one path, run one way and later
// back (SplitSeam may still find a piece that is not simple).
bool IsSeamLoop(const std::vector<CurveUse>& loop, std::string* why = nullptr);
bool SplitSeam(const NetworkGraph& graph, const std::vector<CurveUse>& loop,
               SeamSplit* out, std::string* why);

}  // namespace dot

#endif  // DOT_CORE_NETWORK_SEAM_H_
