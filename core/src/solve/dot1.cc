// SPDX-License-Identifier: AGPL-3.0-or-later
// DOT1 / GK1 (paper, Figure 2 left), iterative: best[e] is the cost of the
// optimal triangulation of the chain under edge e.
#include <chrono>

#include "solve/solvers.h"
#include "solve/tiling.h"
#include "util/run_control.h"

namespace dot {
Status SolveDot1(const Adjacency& adj, const CandidateWeights& weight,
                 const Control& control, DpSolution* out) {
  const auto t0 = std::chrono::steady_clock::now();
  const int32_t edges = adj.edge_count();
  // Filled in edge order by the pass itself: no up-front initialization.
  Table<double> best;
  Table<int32_t> arg;
  best.reserve(edges);
  arg.reserve(edges);
  RunTicker ticker(control, Stage::kDynamicProgram);
  int64_t work = 0;  // since the last poll (RunTicker::Advance)
  for (int32_t e = 0; e < edges; ++e) {
    if (adj.IsPolygonEdge(e)) {
      best.push_back(0);
      arg.push_back(-1);
      continue;
    }
    double b = kInf;
    int32_t bu = -1;
    for (int32_t i = adj.inner_begin[e]; i < adj.inner_begin[e + 1]; ++i) {
      const int32_t u = adj.inner[i];
      const double c = weight[u] + best[adj.tri_edges[3 * u]] +
                       best[adj.tri_edges[3 * u + 1]];
      if (c < b) {
        b = c;
        bu = u;
      }
    }
    if (!ticker.Advance(work, adj.inner_begin[e + 1] - adj.inner_begin[e] + 1,
                        double(e) / edges)) {
      return ticker.status();
    }
    best.push_back(b);
    arg.push_back(bu);
  }
  out->states = edges;
  out->table_bytes =
      static_cast<int64_t>(edges) * (sizeof(double) + sizeof(int32_t));
  out->dp_ms = MsSince(t0);
  if (adj.root < 0 || arg[adj.root] < 0) {
    return MakeStatus(StatusCode::kNoTriangulation, "");
  }

  const auto t1 = std::chrono::steady_clock::now();
  out->cost = best[adj.root];
  CollectTiling(
      adj, arg[adj.root],
      [&](int32_t u, int s) { return arg[adj.tri_edges[3 * u + s]]; },
      &out->triangles);
  out->tiling_ms = MsSince(t1);
  return OkStatus();
}

}  // namespace dot
