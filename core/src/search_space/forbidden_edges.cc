// SPDX-License-Identifier: AGPL-3.0-or-later
#include "search_space/forbidden_edges.h"

#include <algorithm>

#include "mesh/edge_index.h"

namespace dot {

void DropForbiddenEdges(
    const PolygonLoop& loop,
    const std::vector<std::pair<int32_t, int32_t>>& forbidden,
    std::vector<Triangle>* triangles) {
  if (forbidden.empty()) return;
  std::vector<uint64_t> keys;
  keys.reserve(forbidden.size());
  for (const auto& [a, b] : forbidden) keys.push_back(UndirectedEdgeKey(a, b));
  std::sort(keys.begin(), keys.end());
  auto is_forbidden = [&](int32_t p, int32_t q) {
    return std::binary_search(keys.begin(), keys.end(),
                              UndirectedEdgeKey(loop.ids[p], loop.ids[q]));
  };
  triangles->erase(std::remove_if(triangles->begin(), triangles->end(),
                                  [&](const Triangle& t) {
                                    return is_forbidden(t[0], t[1]) ||
                                           is_forbidden(t[1], t[2]) ||
                                           is_forbidden(t[0], t[2]);
                                  }),
                   triangles->end());
}

}  // namespace dot
