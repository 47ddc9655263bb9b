// SPDX-License-Identifier: AGPL-3.0-or-later
// Reference minimum by enumerating every triangulation of a small polygon
// (positions 0..n-1) whose triangles lie in a candidate set, costed
// directly with dot::EvaluateMetrics: independent of the dynamic programs.
#ifndef DOT_TESTS_BRUTE_FORCE_H_
#define DOT_TESTS_BRUTE_FORCE_H_

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <vector>

#include "dot/metrics.h"

namespace dot::testing {

// All triangulations of the chain i..j closed by edge [i, j].
inline void EnumerateChain(int i, int j, const std::set<Triangle>& allowed,
                           std::vector<std::vector<Triangle>>* out) {
  out->clear();
  if (j - i == 1) {
    out->push_back({});
    return;
  }
  for (int k = i + 1; k < j; ++k) {
    if (!allowed.count({i, k, j})) continue;
    std::vector<std::vector<Triangle>> left, right;
    EnumerateChain(i, k, allowed, &left);
    EnumerateChain(k, j, allowed, &right);
    for (const auto& l : left) {
      for (const auto& r : right) {
        std::vector<Triangle> t = l;
        t.insert(t.end(), r.begin(), r.end());
        t.push_back({i, k, j});
        out->push_back(std::move(t));
      }
    }
  }
}

struct BruteForceResult {
  int triangulations = 0;
  double best = std::numeric_limits<double>::infinity();
};

inline BruteForceResult BruteForceMinimum(const std::vector<Vec3>& v,
                                          const std::vector<Vec3>& normals,
                                          const std::set<Triangle>& allowed,
                                          const MetricWeights& w) {
  std::vector<std::vector<Triangle>> all;
  EnumerateChain(0, static_cast<int>(v.size()) - 1, allowed, &all);
  BruteForceResult r;
  r.triangulations = static_cast<int>(all.size());
  for (const auto& t : all) {
    r.best = std::min(r.best, WeightedTotal(w, EvaluateMetrics(v, normals, t)));
  }
  return r;
}

}  // namespace dot::testing

#endif  // DOT_TESTS_BRUTE_FORCE_H_
