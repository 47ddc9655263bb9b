// SPDX-License-Identifier: AGPL-3.0-or-later
// 64-bit keys for undirected edges, for sort-based adjacency.
#ifndef DOT_CORE_MESH_EDGE_KEY_H_
#define DOT_CORE_MESH_EDGE_KEY_H_

#include <algorithm>
#include <cstdint>

namespace dot {

inline uint64_t UndirectedEdgeKey(int32_t a, int32_t b) {
  const uint32_t lo = static_cast<uint32_t>(std::min(a, b));
  const uint32_t hi = static_cast<uint32_t>(std::max(a, b));
  return (uint64_t{lo} << 32) | hi;
}
inline int32_t EdgeKeyLo(uint64_t k) { return static_cast<int32_t>(k >> 32); }
inline int32_t EdgeKeyHi(uint64_t k) {
  return static_cast<int32_t>(k & 0xffffffffu);
}

}  // namespace dot

#endif  // DOT_CORE_MESH_EDGE_KEY_H_
