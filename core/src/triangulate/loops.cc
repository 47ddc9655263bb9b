// SPDX-License-Identifier: AGPL-3.0-or-later
#include "triangulate/loops.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>

#include "dot/validate.h"
#include "mesh/edge_index.h"
#include "polygon/input_check.h"
#include "search_space/all_triangles.h"
#include "search_space/delaunay3d.h"
#include "search_space/forbidden_edges.h"
#include "search_space/planar_cdt.h"
#include "solve/annulus.h"
#include "solve/bridged.h"
#include "util/run_control.h"

namespace dot {
namespace {

using Clock = std::chrono::steady_clock;

// Loop l's positions in `loop`, in order.
std::vector<int32_t> LoopPositions(const PolygonLoop& loop, int32_t l) {
  int32_t begin = 0;
  for (int32_t i = 0; i < l; ++i) begin += loop.sizes[i];
  std::vector<int32_t> p(loop.sizes[l]);
  for (int32_t i = 0; i < loop.sizes[l]; ++i) p[i] = begin + i;
  return p;
}

SurfaceCosts CostsOf(const PolygonLoop& loop, const MetricWeights& weights) {
  SurfaceCosts c;
  c.points = loop.Points();
  if (weights[Metric::kNormalDeviation] != 0) {
    for (int32_t id : loop.ids) c.normals.push_back(loop.normals[id]);
  }
  c.edge_normals = loop.EdgeNormalsByPosition();
  c.weights = weights;
  c.weights[Metric::kDihedral] = 0;
  c.weights[Metric::kSquaredDihedral] = 0;
  c.bending = {weights[Metric::kDihedral], weights[Metric::kSquaredDihedral]};
  return c;
}

// Loop edges (as vertex ids) on no candidate triangle.
std::vector<std::pair<int32_t, int32_t>> MissingLoopEdges(
    const PolygonLoop& loop, const std::vector<Triangle>& triangles) {
  const EdgeIndex index = BuildEdgeIndex(triangles);
  const std::vector<int32_t> next = loop.Successors();
  std::vector<std::pair<int32_t, int32_t>> missing;
  for (int32_t i = 0; i < loop.size(); ++i) {
    if (!HasEdge(index, i, next[i])) {
      missing.emplace_back(loop.ids[i], loop.ids[next[i]]);
    }
  }
  return missing;
}

// The cheaper annulus with loop B as given or (when allowed) reversed.
// When B may not be reversed and no surface exists, `*only_reversed` says
// whether one would with B reversed (for the message).
Status SolveTwo(const PolygonLoop& loop, const std::vector<Triangle>& tris,
                const MetricWeights& weights, const Options& options,
                const Control& control, AnnulusSolution* best, bool* reversed,
                bool* only_reversed) {
  const SurfaceCosts costs = CostsOf(loop, weights);
  const std::vector<int32_t> a = LoopPositions(loop, 0);
  std::vector<int32_t> b = LoopPositions(loop, 1);
  Status s = SolveAnnulus(a, b, tris, costs, options.memory_budget_bytes, kInf,
                          control, best);
  *reversed = *only_reversed = false;
  if (!s.ok() && s.code != StatusCode::kNoTriangulation) return s;
  // Edge face normals fix each loop's direction (the surrounding faces).
  const bool may_reverse = options.reorient_loops && costs.edge_normals.empty();
  if (!may_reverse && s.ok()) return s;
  std::reverse(b.begin(), b.end());
  AnnulusSolution flipped;
  flipped.states = best->states;
  // Reversed, it must beat the first direction's cost to count.
  const Status f = SolveAnnulus(a, b, tris, costs, options.memory_budget_bytes,
                                s.ok() ? best->cost : kInf, control, &flipped);
  best->states = flipped.states;
  if (!f.ok() && f.code != StatusCode::kNoTriangulation) return f;
  if (!may_reverse) {
    *only_reversed = f.ok();
    return s;
  }
  if (f.ok()) {
    *best = std::move(flipped);
    *reversed = true;
    return f;
  }
  return s;
}

Status Solve(const std::vector<Triangle>& tris, const MetricWeights& weights,
             const Options& options, const Control& control, PolygonLoop* loop,
             Result* r) {
  auto t0 = Clock::now();
  AnnulusSolution sol;
  bool reversed = false, only_reversed = false;
  r->non_delaunay_edges.clear();
  r->reversed_loops.clear();
  r->bridges.clear();
  Status s;
  if (loop->LoopCount() > 2) {
    // Beyond two loops: bridges first, then the exact DP over the polygon
    // they make (solve/bridged.h); the loops keep their directions.
    std::vector<std::vector<int32_t>> members;
    for (int32_t l = 0; l < loop->LoopCount(); ++l) {
      members.push_back(LoopPositions(*loop, l));
    }
    BridgedSolution bridged;
    s = SolveBridged(members, tris, CostsOf(*loop, weights),
                     options.memory_budget_bytes, control, &bridged);
    sol.states = bridged.states;
    sol.table_bytes = bridged.table_bytes;
    sol.triangles = std::move(bridged.triangles);
    for (const auto& [p, q] : bridged.bridges) {
      r->bridges.emplace_back(loop->ids[p], loop->ids[q]);
    }
  } else {
    s = SolveTwo(*loop, tris, weights, options, control, &sol, &reversed,
                 &only_reversed);
  }
  r->stats.search_triangles = static_cast<int64_t>(tris.size());
  r->stats.dp_states = sol.states;
  r->stats.table_bytes = sol.table_bytes;
  r->stats.dp_ms += MsSince(t0);
  const bool bi = HasBiTriangleWeight(weights);
  const bool all = r->space_used == SpaceUsed::kAll;
  r->solver = bi ? (all ? Solver::kGk2 : Solver::kDot2)
                 : (all ? Solver::kGk1 : Solver::kDot1);
  if (s.code == StatusCode::kNoTriangulation) {
    r->non_delaunay_edges = MissingLoopEdges(*loop, tris);
    std::ostringstream m;
    if (!r->non_delaunay_edges.empty()) {
      m << r->non_delaunay_edges.size()
        << " loop edges are not on any candidate triangle:";
      for (size_t k = 0; k < r->non_delaunay_edges.size() && k < 10; ++k) {
        m << " " << r->non_delaunay_edges[k].first << "-"
          << r->non_delaunay_edges[k].second;
      }
      if (r->non_delaunay_edges.size() > 10) m << " ...";
      m << (all ? "" : " (edge protection splits them)");
    } else if (loop->LoopCount() > 2) {
      m << "three or more loops keep their given directions (the surface "
        << "on the left of each: rims that face each other, as the small "
        << "rims of a branch and the wide one, run opposite ways; reverse a "
        << "loop drawn the other way round); " << s.message
        << " (approximate: bridges first, then the optimum for them)";
    } else if (only_reversed) {
      m << "no surface joins the loops with loop 1 running its given way; "
           "one does with it reversed (let the solver reverse loops: drop "
           "keep_loop_directions"
        << (loop->edge_normals.empty() ? "" : ", or give no edge face normals")
        << ")";
    } else {
      m << "no surface joining the " << loop->LoopCount()
        << " loops exists among the "
        << (all         ? "triangles on their vertices"
            : r->planar ? "triangles of their planar constrained Delaunay "
                          "triangulation (in one plane, a surface "
                          "joins two loops only when one encloses the "
                          "other)"
                        : "triangles of their Delaunay tetrahedralization");
    }
    s.message = m.str();
    return s;
  }
  if (!s.ok()) return s;
  r->triangles.clear();
  for (const Triangle& t : sol.triangles) {
    r->triangles.push_back({loop->ids[t[0]], loop->ids[t[1]], loop->ids[t[2]]});
  }
  if (reversed) r->reversed_loops.push_back(1);
  return OkStatus();
}

}  // namespace

namespace {

Status SolveLoopsOnce(const PlaneFit& fit, bool planar,
                      const MetricWeights& weights, const Problem& problem,
                      const Options& options, const Control& control,
                      PolygonLoop* loop, Result* r);

}  // namespace

Status SolveLoops(const PlaneFit& fit, bool planar,
                  const MetricWeights& weights, const Problem& problem,
                  const Options& options, const Control& control,
                  PolygonLoop* loop, Result* r) {
  Status s =
      SolveLoopsOnce(fit, planar, weights, problem, options, control, loop, r);
  if (!s.ok()) {
    r->reversed_loops.clear();
    return s;
  }
  if (!r->reversed_loops.empty()) {
    // Listed as the surface runs along it: reversed, from its first vertex.
    const std::vector<int32_t> b = LoopPositions(*loop, 1);
    std::reverse(loop->ids.begin() + b.front() + 1,
                 loop->ids.begin() + b.back() + 1);
  }
  return s;
}

namespace {

Status SolveLoopsOnce(const PlaneFit& fit, bool planar,
                      const MetricWeights& weights, const Problem& problem,
                      const Options& options, const Control& control,
                      PolygonLoop* loop, Result* r) {
  const int32_t k = loop->LoopCount();
  {
    int32_t begin = 0;
    for (int32_t l = 0; l < k; ++l) {
      std::vector<Vec3> points(loop->vertices.begin() + begin,
                               loop->vertices.begin() + begin + loop->sizes[l]);
      if (Status s =
              CheckNotCollinear(FitPlane(points), loop->sizes[l], options);
          !s.ok()) {
        return InvalidArgument("loop " + std::to_string(l) + ": " + s.message);
      }
      begin += loop->sizes[l];
    }
  }
  const PolygonLoop input = *loop;
  std::vector<Triangle> tris;
  Status s;
  if (options.space != SearchSpace::kAll) {
    auto t0 = Clock::now();
    r->space_used =
        planar ? SpaceUsed::kPlanarDelaunay2d : SpaceUsed::kDelaunay3d;
    if (planar) {
      s = PlanarCdtTriangles(loop->Points(), loop->Successors(),
                             fit.dominant_axis, &tris);
      r->stats.delaunay_triangles = static_cast<int64_t>(tris.size());
    } else {
      s = Delaunay3dFaces(options, control, loop, &tris, &r->stats);
    }
    r->stats.delaunay_ms = MsSince(t0);
    if (!s.ok()) return s;
    DropForbiddenEdges(*loop, problem.forbidden_edges, &tris);
    s = Solve(tris, weights, options, control, loop, r);
  }
  const bool fallback = options.space == SearchSpace::kAuto &&
                        s.code == StatusCode::kNoTriangulation &&
                        input.size() <= options.all_space_max_vertices;
  if (options.space != SearchSpace::kAll && !fallback) return s;
  const std::string first_reason = s.message;
  *loop = input;
  if (loop->size() > options.all_space_hard_limit) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "search space 'all' is limited to " +
                          std::to_string(options.all_space_hard_limit) +
                          " vertices; the loops have " +
                          std::to_string(loop->size()));
  }
  const int64_t n = loop->size();
  const int64_t estimate = EstimateAnnulusBytes(n * (n - 1) * (n - 2) / 6);
  if (estimate > options.memory_budget_bytes) {
    // Refused before the triangles are listed.
    return MakeStatus(StatusCode::kResourceExhausted,
                      "estimated memory " + std::to_string(estimate >> 20) +
                          " MiB for all triangles on " + std::to_string(n) +
                          " vertices exceeds the budget of " +
                          std::to_string(options.memory_budget_bytes >> 20) +
                          " MiB");
  }
  r->space_used = SpaceUsed::kAll;
  auto t0 = Clock::now();
  s = AllTriangles(loop->Points(), control, &tris);
  r->stats.delaunay_ms += MsSince(t0);
  if (!s.ok()) return s;
  DropForbiddenEdges(*loop, problem.forbidden_edges, &tris);
  s = Solve(tris, weights, options, control, loop, r);
  if (!s.ok() || !fallback) return s;
  // `auto` answers OK only with an intersection-free surface.
  r->intersecting_pairs = CountIntersectingPairs(loop->vertices, r->triangles);
  if (r->intersecting_pairs > 0) {
    r->triangles.clear();
    return MakeStatus(
        StatusCode::kNoTriangulation,
        "no intersection-free surface found: " + first_reason +
            "; and the optimum over all triangles self-intersects (" +
            std::to_string(r->intersecting_pairs) +
            " pairs); try protect_edges, or ask for search space 'all' to get "
            "that self-intersecting optimum");
  }
  return OkStatus();
}

}  // namespace

}  // namespace dot
