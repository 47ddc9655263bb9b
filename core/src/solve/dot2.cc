// SPDX-License-Identifier: AGPL-3.0-or-later
// DOT2 / GK2 (paper, Figure 2 right), iterative. The paper's state
// {e, t'} is a slot of the outer triangle t' (its short edge e): slot_cost
// holds the optimal cost of the chain under e given that t' lies across e.
//
// For an edge e with inner triangles u and outer slots t':
//   slot_cost[t'] = min_u  B(u) + bend(u, t'),
//   B(u) = w(u) + slot_cost[u, slot 0] + slot_cost[u, slot 1].
// B does not depend on t', so it is computed once per edge, sorted, and the
// scan for each t' stops as soon as B(u) + min(bend) cannot beat the best so
// far: exact, and usually far fewer than |inner| * |outer| evaluations.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "dot/metrics.h"
#include "solve/solvers.h"
#include "solve/tiling.h"
#include "util/flat_vector.h"
#include "util/run_control.h"

namespace dot {
namespace {

struct InnerCandidate {
  double b;
  int32_t u;
  int32_t rank;  // position in the edge's (canonically ordered) inner list
  Vec3 normal;
};

}  // namespace

double MinBending(BendingWeights w) {
  double lo = std::min(0.0, w.dihedral * kPi + w.squared_dihedral * kPi * kPi);
  if (w.squared_dihedral > 0) {
    const double vertex = -w.dihedral / (2 * w.squared_dihedral);
    if (vertex > 0 && vertex < kPi) {
      lo = std::min(lo,
                    w.dihedral * vertex + w.squared_dihedral * vertex * vertex);
    }
  }
  return lo;
}

Status SolveDot2(const Adjacency& adj, const CandidateWeights& weight,
                 const CandidateNormals& unit_normals,
                 const std::vector<Vec3>& edge_normals, BendingWeights bending,
                 const Control& control, DpSolution* out) {
  const auto t0 = std::chrono::steady_clock::now();
  const int32_t edges = adj.edge_count();
  const size_t slots = 2 * weight.size();
  RunTicker ticker(control, Stage::kDynamicProgram);
  FlatVector<double> slot_cost(slots);
  FlatVector<int32_t> slot_arg(slots);
  if (!ForEachPolled(ticker, slots, [&](size_t i) {
        slot_cost[i] = kInf;
        slot_arg[i] = -1;
        return true;
      })) {
    return ticker.status();
  }
  const double min_bend = MinBending(bending);
  auto bend = [&](const Vec3& a, const Vec3& b) {
    const double theta = BendingAngle(a, b);
    return bending.dihedral * theta + bending.squared_dihedral * theta * theta;
  };
  // The bending against the surface face across polygon edge `pos`, if any.
  auto boundary_bend = [&](int32_t pos, const Vec3& patch_normal) {
    if (edge_normals.empty() || Norm(edge_normals[pos]) == 0) return 0.0;
    return bend(edge_normals[pos], patch_normal);
  };

  std::vector<InnerCandidate> cand;
  int64_t work = 0;  // since the last poll (RunTicker::Advance)
  double root_cost = kInf;
  int32_t root_arg = -1;
  for (int32_t e = 0; e < edges; ++e) {
    const int32_t ob = adj.outer_begin[e], oe = adj.outer_begin[e + 1];
    if (adj.IsPolygonEdge(e)) {
      for (int32_t i = ob; i < oe; ++i) {
        const int32_t slot = adj.outer[i];
        slot_cost[slot] = boundary_bend(adj.edge_lo[e], unit_normals[slot / 2]);
      }
      if (!ticker.Advance(work, oe - ob)) return ticker.status();
      continue;
    }
    if (!ticker.Advance(work, adj.inner_begin[e + 1] - adj.inner_begin[e] + 1,
                        double(e) / edges)) {
      return ticker.status();
    }
    cand.clear();
    for (int32_t i = adj.inner_begin[e]; i < adj.inner_begin[e + 1]; ++i) {
      const int32_t u = adj.inner[i];
      const double b = weight[u] + slot_cost[2 * u] + slot_cost[2 * u + 1];
      if (b < kInf) cand.push_back({b, u, i, unit_normals[u]});
    }
    if (cand.empty()) continue;
    std::sort(cand.begin(), cand.end(),
              [](const InnerCandidate& x, const InnerCandidate& y) {
                // Ties by list position, not triangle id: results must not
                // depend on the order a backend listed the faces in.
                return x.b < y.b || (x.b == y.b && x.rank < y.rank);
              });
    if (e == adj.root) {
      // The root is the polygon edge n-1 -> 0: its inner triangle may bend
      // against a surface face too.
      for (const InnerCandidate& c : cand) {
        if (c.b + min_bend >= root_cost) break;
        const double v = c.b + boundary_bend(adj.n - 1, c.normal);
        if (v < root_cost) {
          root_cost = v;
          root_arg = c.u;
        }
      }
      continue;
    }
    for (int32_t i = ob; i < oe; ++i) {
      const int32_t slot = adj.outer[i];
      const Vec3 nt = unit_normals[slot / 2];
      double best = kInf;
      int32_t best_u = -1;
      int64_t visited = 1;
      for (const InnerCandidate& c : cand) {
        if (c.b + min_bend >= best) break;
        ++visited;
        const double v = c.b + bend(c.normal, nt);
        if (v < best) {
          best = v;
          best_u = c.u;
        }
      }
      slot_cost[slot] = best;
      slot_arg[slot] = best_u;
      if (!ticker.Advance(work, visited, double(e) / edges)) {
        return ticker.status();
      }
    }
  }
  out->states = static_cast<int64_t>(adj.outer.size()) + 1;
  out->table_bytes =
      static_cast<int64_t>(slots * (sizeof(double) + sizeof(int32_t)));
  out->dp_ms = MsSince(t0);
  if (root_arg < 0) return MakeStatus(StatusCode::kNoTriangulation, "");

  const auto t1 = std::chrono::steady_clock::now();
  out->cost = root_cost;
  CollectTiling(
      adj, root_arg, [&](int32_t u, int s) { return slot_arg[2 * u + s]; },
      &out->triangles);
  out->tiling_ms = MsSince(t1);
  return OkStatus();
}

}  // namespace dot
