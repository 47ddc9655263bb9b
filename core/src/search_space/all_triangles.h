// SPDX-License-Identifier: AGPL-3.0-or-later
// The unrestricted search space of GK1/GK2: every triangle on the polygon's
// vertices. Theta(n^3) triangles, so only for small polygons.
#ifndef DOT_CORE_SEARCH_SPACE_ALL_TRIANGLES_H_
#define DOT_CORE_SEARCH_SPACE_ALL_TRIANGLES_H_

#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/problem.h"
#include "dot/status.h"

namespace dot {

// Every non-degenerate triangle on loop positions 0..n-1, each sorted
// ascending. Polls `control`.
Status AllTriangles(const std::vector<Vec3>& loop, const Control& control,
                    std::vector<Triangle>* triangles);

}  // namespace dot

#endif  // DOT_CORE_SEARCH_SPACE_ALL_TRIANGLES_H_
