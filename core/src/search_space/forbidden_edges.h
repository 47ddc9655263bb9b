// SPDX-License-Identifier: AGPL-3.0-or-later
// Removes candidate triangles that use a forbidden chord: an edge the
// surrounding mesh already has (Problem::forbidden_edges), which a patch
// must not add a second time.
#ifndef DOT_CORE_SEARCH_SPACE_FORBIDDEN_EDGES_H_
#define DOT_CORE_SEARCH_SPACE_FORBIDDEN_EDGES_H_

#include <cstdint>
#include <utility>
#include <vector>

#include "dot/geometry.h"
#include "polygon/polygon_loop.h"

namespace dot {

// `triangles` are over loop positions; `forbidden` over vertex ids (the
// loop's ids). Keeps the order of the remaining triangles.
void DropForbiddenEdges(
    const PolygonLoop& loop,
    const std::vector<std::pair<int32_t, int32_t>>& forbidden,
    std::vector<Triangle>* triangles);

}  // namespace dot

#endif  // DOT_CORE_SEARCH_SPACE_FORBIDDEN_EDGES_H_
