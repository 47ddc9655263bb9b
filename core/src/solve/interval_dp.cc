// SPDX-License-Identifier: AGPL-3.0-or-later
#include "solve/interval_dp.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solve/solvers.h"
#include "util/run_control.h"

namespace dot {
namespace {

// The weighted per-triangle cost of (a, b, c), only the weighted metrics
// evaluated (this runs n^3 / 6 times); `cross` is (b - a) x (c - a).
double TriangleCost(const IntervalDpInput& in, int32_t a, int32_t b, int32_t c,
                    const Vec3& cross, double twice_area) {
  const MetricWeights& w = in.weights;
  double cost = 0;
  if (w[Metric::kArea] != 0) cost += w[Metric::kArea] * 0.5 * twice_area;
  const bool lengths = w[Metric::kPerimeter] != 0 || w[Metric::kShape] != 0;
  if (lengths) {
    const Vec3 &pa = in.points[a], &pb = in.points[b], &pc = in.points[c];
    const double ab = Distance(pa, pb), bc = Distance(pb, pc),
                 ca = Distance(pc, pa);
    if (w[Metric::kPerimeter] != 0) {
      cost += w[Metric::kPerimeter] * (ab + bc + ca);
    }
    if (w[Metric::kShape] != 0) {
      const double sq = ab * ab + bc * bc + ca * ca;
      cost += w[Metric::kShape] *
              std::max(0.0, 1.0 - 2.0 * std::sqrt(3.0) * twice_area / sq);
    }
  }
  if (w[Metric::kNormalDeviation] != 0) {
    const Vec3 n = (1.0 / twice_area) * cross;
    double dev = 0;
    for (int32_t v : {a, b, c}) dev += BendingAngle(n, in.normals[v]);
    cost += w[Metric::kNormalDeviation] * dev;
  }
  return cost;
}

}  // namespace

int64_t IntervalDpBytes(int64_t n, bool bending) {
  // Per (i, k): count, cost, apex, preferred-apex offset, forbidden flag,
  // and with bending the apex triangle's normal.
  return n * n *
         static_cast<int64_t>(sizeof(int32_t) * 3 + sizeof(double) + 1 +
                              (bending ? sizeof(Vec3) : 0));
}

Status SolveIntervalDp(const IntervalDpInput& in, const Control& control,
                       IntervalDpSolution* out) {
  *out = {};
  const auto n = static_cast<int32_t>(in.points.size());
  if (n < 3) return MakeStatus(StatusCode::kNoTriangulation, "");
  const auto cells = static_cast<size_t>(n) * n;
  auto at = [n](int32_t i, int32_t k) {
    return static_cast<size_t>(i) * n + k;
  };

  std::vector<uint8_t> forbidden(cells, 0);
  for (auto [a, b] : in.forbidden) {
    if (a < 0 || b < 0 || a >= n || b >= n || a == b) continue;
    forbidden[at(std::min(a, b), std::max(a, b))] = 1;
  }
  // Preferred apexes per chain (i, k), i < k: a sorted triangle a < b < c
  // is a candidate of chain (a, c) with apex b only.
  std::vector<int32_t> pref_begin(cells + 1, 0), pref_apex;
  for (const Triangle& t : in.preferred) {
    Triangle s = t;
    std::sort(s.begin(), s.end());
    if (s[0] < 0 || s[2] >= n || s[0] == s[1] || s[1] == s[2]) continue;
    ++pref_begin[at(s[0], s[2]) + 1];
  }
  for (size_t c = 0; c < cells; ++c) pref_begin[c + 1] += pref_begin[c];
  pref_apex.resize(pref_begin[cells]);
  {
    std::vector<int32_t> fill(pref_begin.begin(), pref_begin.end() - 1);
    for (const Triangle& t : in.preferred) {
      Triangle s = t;
      std::sort(s.begin(), s.end());
      if (s[0] < 0 || s[2] >= n || s[0] == s[1] || s[1] == s[2]) continue;
      pref_apex[fill[at(s[0], s[2])]++] = s[1];
    }
  }

  const MetricWeights& w = in.weights;
  const BendingWeights bending{w[Metric::kDihedral],
                               w[Metric::kSquaredDihedral]};
  const bool bends = bending.dihedral != 0 || bending.squared_dihedral != 0;
  auto bend = [&](const Vec3& a, const Vec3& b) {
    if (Norm(a) == 0) return 0.0;  // no face across a boundary edge
    const double theta = BendingAngle(a, b);
    return bending.dihedral * theta + bending.squared_dihedral * theta * theta;
  };
  auto edge_normal = [&](int32_t i) {
    return in.edge_normals.empty() ? Vec3{} : in.edge_normals[i];
  };

  constexpr int32_t kNone = std::numeric_limits<int32_t>::max();
  std::vector<int32_t> count(cells, kNone), apex(cells, -1);
  std::vector<double> cost(cells, kInf);
  std::vector<Vec3> normal(bends ? cells : 0);
  std::vector<uint8_t> is_preferred(n, 0);
  out->table_bytes = IntervalDpBytes(n, bends);

  RunTicker ticker(control, Stage::kDynamicProgram);
  int64_t work = 0;  // since the last poll (RunTicker::Advance)
  for (int32_t i = 0; i + 1 < n; ++i)
    count[at(i, i + 1)] = 0, cost[at(i, i + 1)] = 0;
  for (int32_t span = 2; span < n; ++span) {
    const double done = double(span) / n;
    for (int32_t i = 0; i + span < n; ++i) {
      const int32_t k = i + span;
      const size_t ik = at(i, k);
      // The closing edge (0, n-1) is a polygon edge, never forbidden.
      if (forbidden[ik] && span != n - 1) continue;
      for (int32_t p = pref_begin[ik]; p < pref_begin[ik + 1]; ++p) {
        is_preferred[pref_apex[p]] = 1;
      }
      const Vec3& pi = in.points[i];
      const Vec3 ik_vec = in.points[k] - pi;
      int32_t best_count = kNone, best_apex = -1;
      double best_cost = kInf;
      Vec3 best_normal;
      if (!ticker.Advance(work, span, done)) return ticker.status();
      for (int32_t m = i + 1; m < k; ++m) {
        const size_t im = at(i, m), mk = at(m, k);
        if (count[im] == kNone || count[mk] == kNone) continue;
        const int32_t c = count[im] + count[mk] + (is_preferred[m] ? 0 : 1);
        if (c > best_count) continue;
        const Vec3 cross = Cross(in.points[m] - pi, ik_vec);
        const double twice_area = Norm(cross);
        if (twice_area == 0) continue;
        double total =
            cost[im] + cost[mk] + TriangleCost(in, i, m, k, cross, twice_area);
        Vec3 unit;
        if (bends) {
          unit = (1.0 / twice_area) * cross;
          total += bend(m == i + 1 ? edge_normal(i) : normal[im], unit);
          total += bend(k == m + 1 ? edge_normal(m) : normal[mk], unit);
          if (span == n - 1) total += bend(edge_normal(n - 1), unit);
        }
        if (c < best_count || total < best_cost) {
          best_count = c;
          best_cost = total;
          best_apex = m;
          best_normal = unit;
        }
      }
      for (int32_t p = pref_begin[ik]; p < pref_begin[ik + 1]; ++p) {
        is_preferred[pref_apex[p]] = 0;
      }
      count[ik] = best_count;
      cost[ik] = best_cost;
      apex[ik] = best_apex;
      if (bends) normal[ik] = best_normal;
    }
  }
  const size_t root = at(0, n - 1);
  if (apex[root] < 0) return MakeStatus(StatusCode::kNoTriangulation, "");
  out->cost = cost[root];
  out->not_preferred = count[root];
  std::vector<std::pair<int32_t, int32_t>> stack = {{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, k] = stack.back();
    stack.pop_back();
    const int32_t m = apex[at(i, k)];
    out->triangles.push_back({i, m, k});
    if (m > i + 1) stack.emplace_back(i, m);
    if (k > m + 1) stack.emplace_back(m, k);
  }
  return OkStatus();
}

}  // namespace dot
