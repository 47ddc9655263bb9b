// SPDX-License-Identifier: AGPL-3.0-or-later
// Disjoint sets over 0..n-1 (path halving, no ranks: the joins here follow
// mesh adjacency and stay shallow). Components of a mesh, fans around a
// vertex, holes that share a vertex.
#ifndef DOT_CORE_UTIL_UNION_FIND_H_
#define DOT_CORE_UTIL_UNION_FIND_H_

#include <cstdint>
#include <numeric>
#include <vector>

namespace dot {

class UnionFind {
 public:
  explicit UnionFind(size_t count) : parent_(count) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int32_t Find(int32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void Join(int32_t a, int32_t b) { parent_[Find(a)] = Find(b); }
  // The number of disjoint sets.
  int64_t Count() {
    int64_t roots = 0;
    for (size_t x = 0; x < parent_.size(); ++x) {
      roots += Find(static_cast<int32_t>(x)) == static_cast<int32_t>(x);
    }
    return roots;
  }

 private:
  std::vector<int32_t> parent_;
};

}  // namespace dot

#endif  // DOT_CORE_UTIL_UNION_FIND_H_
