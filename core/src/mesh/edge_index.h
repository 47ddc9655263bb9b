// SPDX-License-Identifier: AGPL-3.0-or-later
// The one edge index of the library: every topology question about a
// triangle set (the neighbour across a side, boundary and non-manifold
// edges, orientation, whether an edge exists) is answered from it. Each side
// of each triangle is a record; records are sorted by undirected edge, then
// triangle, then side, so the uses of one edge are adjacent and in a
// deterministic order.
#ifndef DOT_CORE_MESH_EDGE_INDEX_H_
#define DOT_CORE_MESH_EDGE_INDEX_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "dot/geometry.h"
#include "util/flat_vector.h"
#include "util/run_control.h"

namespace dot {

// 64-bit key of an undirected edge: its lower vertex id, then the higher.
inline uint64_t UndirectedEdgeKey(int32_t a, int32_t b) {
  const uint32_t lo = static_cast<uint32_t>(std::min(a, b));
  const uint32_t hi = static_cast<uint32_t>(std::max(a, b));
  return (uint64_t{lo} << 32) | hi;
}
inline int32_t EdgeKeyLo(uint64_t k) { return static_cast<int32_t>(k >> 32); }
inline int32_t EdgeKeyHi(uint64_t k) {
  return static_cast<int32_t>(k & 0xffffffffu);
}

// One use of an edge: side `side` of triangle `triangle` runs from
// t[side] to t[(side + 1) % 3].
struct EdgeUse {
  uint64_t key;      // UndirectedEdgeKey of the side
  int32_t triangle;  // index into the triangle list
  int8_t side;       // 0, 1 or 2
  bool forward;      // the side runs from the lower vertex id to the higher

  int32_t lo() const { return EdgeKeyLo(key); }
  int32_t hi() const { return EdgeKeyHi(key); }
  int32_t from() const { return forward ? lo() : hi(); }
  int32_t to() const { return forward ? hi() : lo(); }
};

struct EdgeIndex {
  // 3 per triangle, sorted (key, triangle, side); not zeroed before it is
  // filled (a scan's index is hundreds of MB).
  FlatVector<EdgeUse> uses;
};

// Indexes every side of every triangle (vertex ids must be >= 0). Linear
// apart from sorting each vertex's handful of edges.
EdgeIndex BuildEdgeIndex(const std::vector<Triangle>& triangles);
// The same for whole meshes (about 60 ms per million triangles), ticking
// `ticker` as it goes: false, with `index` incomplete, once the run must
// stop (ticker.status() says why).
bool BuildEdgeIndex(const std::vector<Triangle>& triangles, RunTicker& ticker,
                    EdgeIndex* index);

// All uses of one undirected edge: a run of EdgeIndex::uses.
struct EdgeUses {
  const EdgeUse* first;
  const EdgeUse* last;

  size_t size() const { return static_cast<size_t>(last - first); }
  const EdgeUse& operator[](size_t i) const { return first[i]; }
  const EdgeUse* begin() const { return first; }
  const EdgeUse* end() const { return last; }
  int32_t lo() const { return first->lo(); }
  int32_t hi() const { return first->hi(); }
};

// Calls fn(const EdgeUses&) once per distinct edge, in increasing key order.
// A fn that returns bool stops the walk by returning false.
template <typename Fn>
void ForEachEdge(const EdgeIndex& index, Fn&& fn) {
  const EdgeUse* const end = index.uses.data() + index.uses.size();
  for (const EdgeUse* first = index.uses.data(); first != end;) {
    const EdgeUse* last = first + 1;
    while (last != end && last->key == first->key) ++last;
    if constexpr (std::is_same_v<decltype(fn(EdgeUses{first, last})), bool>) {
      if (!fn(EdgeUses{first, last})) return;
    } else {
      fn(EdgeUses{first, last});
    }
    first = last;
  }
}

// Whether some triangle of the index has the undirected edge {a, b}.
bool HasEdge(const EdgeIndex& index, int32_t a, int32_t b);

}  // namespace dot

#endif  // DOT_CORE_MESH_EDGE_INDEX_H_
