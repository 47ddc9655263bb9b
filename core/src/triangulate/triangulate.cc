// SPDX-License-Identifier: AGPL-3.0-or-later
// Orchestration: validate -> search space -> adjacency -> DP -> tiling ->
// result. Each stage lives in its own file; this one only wires them.
#include "dot/triangulate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <sstream>

#include "dot/space_cache.h"
#include "dot/validate.h"
#include "polygon/input_check.h"
#include "polygon/plane_fit.h"
#include "polygon/polygon_loop.h"
#include "polygon/unit_scale.h"
#include "search_space/all_triangles.h"
#include "search_space/delaunay3d.h"
#include "search_space/delaunay_cgal.h"
#include "search_space/forbidden_edges.h"
#include "search_space/planar_cdt.h"
#include "solve/adjacency.h"
#include "solve/interval_dp.h"
#include "solve/prepared_space.h"
#include "solve/solvers.h"
#include "triangulate/loops.h"
#include "util/run_control.h"

namespace dot {
namespace {

using Clock = std::chrono::steady_clock;

Status CheckBudget(int64_t triangles, bool bi, const Options& options,
                   Stats* stats) {
  stats->estimated_bytes = EstimateTableBytes(triangles, bi);
  if (stats->estimated_bytes > options.memory_budget_bytes) {
    std::ostringstream s;
    s << "estimated memory " << (stats->estimated_bytes >> 20) << " MiB for "
      << triangles << " candidate triangles exceeds the budget of "
      << (options.memory_budget_bytes >> 20) << " MiB";
    return MakeStatus(StatusCode::kResourceExhausted, s.str());
  }
  return OkStatus();
}

void Report(const Control& control, Stage stage, double fraction) {
  if (control.progress) control.progress(stage, fraction);
}

// The weight-independent half of a solve: adjacency, and the candidates'
// unit normals when `unit_normals` (a space kept for re-solves; DOT2
// computes them as it goes otherwise).
Status BuildSpaceTables(bool unit_normals, const Options& options,
                        const Control& control, bool bi, PreparedSpace* sp,
                        Stats* st) {
  Status s =
      CheckBudget(static_cast<int64_t>(sp->triangles.size()), bi, options, st);
  if (!s.ok()) return s;
  Report(control, Stage::kAdjacency, 0);
  // Sorts the candidates: normals are indexed by the sorted list.
  s = BuildAdjacency(sp->loop.size(), &sp->triangles, control, &sp->adjacency);
  if (!s.ok() || !unit_normals) return s;
  const std::vector<Vec3> points = sp->loop.Points();
  sp->unit_normals.reserve(sp->triangles.size());
  RunTicker ticker(control, Stage::kAdjacency);
  for (const Triangle& t : sp->triangles) {
    if (!ticker.Tick()) return ticker.status();
    sp->unit_normals.push_back(UnitNormal(points, t));
  }
  return OkStatus();
}

// The weight-dependent half: per-triangle weights, the DP and tiling; on
// success fills the result's triangles (as vertex ids) and solver.
Status Solve(const PreparedSpace& sp, const MetricWeights& weights,
             const Options& options, const Control& control, Result* r) {
  const bool bi = HasBiTriangleWeight(weights);
  Stats& st = r->stats;
  Status s =
      CheckBudget(static_cast<int64_t>(sp.triangles.size()), bi, options, &st);
  if (!s.ok()) return s;
  const PolygonLoop& loop = sp.loop;
  const Adjacency& adj = sp.adjacency;
  auto t0 = Clock::now();
  const std::vector<Vec3> points = loop.Points();
  std::vector<Vec3> normals;  // in loop order, only when weighted
  if (weights[Metric::kNormalDeviation] != 0) {
    for (int32_t id : loop.ids) normals.push_back(loop.normals[id]);
  }
  const size_t count = sp.triangles.size();
  CandidateWeights w(count);  // uninitialized: each written once below
  RunTicker ticker(control, Stage::kAdjacency);
  int64_t work = 0;  // a poll every 4,096: a cost is up to ~200 ns
  for (size_t t = 0; t < count; ++t) {
    if (!ticker.Advance(work, 1)) return ticker.status();
    w[t] = WeightedTriangleCost(weights, points, normals, sp.triangles[t]);
  }
  st.search_triangles = static_cast<int64_t>(count);
  st.edges = adj.edge_count();
  st.adjacency_entries =
      static_cast<int64_t>(adj.inner.size() + adj.outer.size());
  st.adjacency_ms += MsSince(t0);

  Report(control, Stage::kDynamicProgram, 0);
  DpSolution sol;
  if (bi) {
    const CandidateNormals unit_normals =
        sp.unit_normals.empty() ? CandidateNormals(points, sp.triangles)
                                : CandidateNormals(sp.unit_normals);
    s = SolveDot2(
        adj, w, unit_normals, loop.EdgeNormalsByPosition(),
        {weights[Metric::kDihedral], weights[Metric::kSquaredDihedral]},
        control, &sol);
  } else {
    s = SolveDot1(adj, w, control, &sol);
  }
  st.dp_states = sol.states;
  st.table_bytes =
      adj.Bytes() +
      static_cast<int64_t>(count * (sizeof(Triangle) + sizeof(double))) +
      static_cast<int64_t>(sp.unit_normals.size() * sizeof(Vec3)) +
      sol.table_bytes;
  st.dp_ms = sol.dp_ms;
  st.tiling_ms = sol.tiling_ms;
  const bool all = sp.space == SpaceUsed::kAll;
  r->solver = bi ? (all ? Solver::kGk2 : Solver::kDot2)
                 : (all ? Solver::kGk1 : Solver::kDot1);
  r->space_used = sp.space;
  if (s.code == StatusCode::kNoTriangulation) {
    r->non_delaunay_edges.clear();
    for (int32_t i : adj.missing_polygon_edges) {
      r->non_delaunay_edges.emplace_back(loop.ids[i],
                                         loop.ids[(i + 1) % loop.size()]);
    }
    std::ostringstream m;
    if (r->non_delaunay_edges.empty()) {
      m << "polygon is not Delaunay-triangulable";
    } else {
      m << r->non_delaunay_edges.size()
        << " polygon edges are not on any Delaunay triangle:";
      for (size_t k = 0; k < r->non_delaunay_edges.size() && k < 10; ++k) {
        m << " " << r->non_delaunay_edges[k].first << "-"
          << r->non_delaunay_edges[k].second;
      }
      if (r->non_delaunay_edges.size() > 10) m << " ...";
      m << " (edge protection splits them)";
    }
    if (all) m.str("no triangulation exists among all triangles");
    s.message = m.str();
    return s;
  }
  if (!s.ok()) return s;
  r->triangles.clear();
  r->triangles.reserve(sol.triangles.size());
  for (int32_t t : sol.triangles) {
    const Triangle& p = sp.triangles[t];
    r->triangles.push_back({loop.ids[p[0]], loop.ids[p[1]], loop.ids[p[2]]});
  }
  return OkStatus();
}

using Chords = std::vector<std::pair<int32_t, int32_t>>;

// The Delaunay search space of the loop, prepared for solving.
Status PrepareDelaunay(const PlaneFit& fit, bool planar, bool unit_normals,
                       bool bi, const Chords& forbidden, const Options& options,
                       const Control& control, PreparedSpace* sp,
                       Stats* stats) {
  Report(control, Stage::kDelaunay, 0);
  auto t0 = Clock::now();
  Status s;
  if (planar) {
    sp->space = SpaceUsed::kPlanarDelaunay2d;
    s = PlanarCdtTriangles(sp->loop.Points(), sp->loop.Successors(),
                           fit.dominant_axis, &sp->triangles);
    stats->delaunay_triangles = static_cast<int64_t>(sp->triangles.size());
  } else {
    sp->space = SpaceUsed::kDelaunay3d;
    s = Delaunay3dFaces(options, control, &sp->loop, &sp->triangles, stats);
  }
  sp->tetrahedra = stats->tetrahedra;
  sp->delaunay_triangles = stats->delaunay_triangles;
  stats->delaunay_ms = MsSince(t0);
  if (!s.ok()) return s;
  t0 = Clock::now();
  DropForbiddenEdges(sp->loop, forbidden, &sp->triangles);
  s = BuildSpaceTables(unit_normals, options, control, bi, sp, stats);
  stats->adjacency_ms = MsSince(t0);
  return s;
}

// All triangles of the loop (GK1/GK2), prepared for solving.
Status PrepareAll(const MetricWeights& weights, const Chords& forbidden,
                  const Options& options, const Control& control,
                  PreparedSpace* sp, Stats* stats) {
  const int64_t n = sp->loop.size();
  if (n > options.all_space_hard_limit) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "search space 'all' is limited to " +
                          std::to_string(options.all_space_hard_limit) +
                          " vertices; the polygon has " + std::to_string(n));
  }
  const bool bi = HasBiTriangleWeight(weights);
  Status s = CheckBudget(n * (n - 1) * (n - 2) / 6, bi, options, stats);
  if (!s.ok()) return s;
  sp->space = SpaceUsed::kAll;
  auto t0 = Clock::now();
  s = AllTriangles(sp->loop.Points(), control, &sp->triangles);
  stats->delaunay_ms += MsSince(t0);
  if (!s.ok()) return s;
  t0 = Clock::now();
  DropForbiddenEdges(sp->loop, forbidden, &sp->triangles);
  s = BuildSpaceTables(false, options, control, bi, sp, stats);
  stats->adjacency_ms += MsSince(t0);
  return s;
}

// Every triangle of one loop, its Delaunay faces first (interval_dp.h).
Status SolveDelaunayFirst(const PlaneFit& fit, bool planar,
                          const MetricWeights& weights, const Problem& problem,
                          const Options& options, const Control& control,
                          const PolygonLoop& loop, Result* r) {
  const int64_t n = loop.size();
  Stats& st = r->stats;
  if (n > options.delaunay_first_max_vertices) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "search space 'delaunay_first' is limited to " +
                          std::to_string(options.delaunay_first_max_vertices) +
                          " vertices; the polygon has " + std::to_string(n));
  }
  st.estimated_bytes = IntervalDpBytes(n, HasBiTriangleWeight(weights));
  if (st.estimated_bytes > options.memory_budget_bytes) {
    return MakeStatus(
        StatusCode::kResourceExhausted,
        "estimated memory " + std::to_string(st.estimated_bytes >> 20) +
            " MiB for the tables of " + std::to_string(n) +
            " vertices exceeds the budget of " +
            std::to_string(options.memory_budget_bytes >> 20) + " MiB");
  }
  // The preferred triangles: the Delaunay faces, without edge protection
  // (the loop keeps its vertices).
  Report(control, Stage::kDelaunay, 0);
  auto t_delaunay = Clock::now();
  IntervalDpInput in;
  Status s;
  if (planar) {
    s = PlanarCdtTriangles(loop.Points(), loop.Successors(), fit.dominant_axis,
                           &in.preferred);
  } else {
    Options plain = options;
    plain.protect_edges = false;
    PolygonLoop copy = loop;
    s = Delaunay3dFaces(plain, control, &copy, &in.preferred, &st);
  }
  st.delaunay_ms = MsSince(t_delaunay);
  if (!s.ok()) return s;
  in.points = loop.Points();
  if (weights[Metric::kNormalDeviation] != 0) {
    for (int32_t id : loop.ids)
      in.normals.push_back(Normalized(loop.normals[id]));
  }
  in.edge_normals = loop.EdgeNormalsByPosition();
  in.weights = weights;
  in.forbidden = problem.forbidden_edges;
  Report(control, Stage::kDynamicProgram, 0);
  const auto t0 = Clock::now();
  IntervalDpSolution sol;
  s = SolveIntervalDp(in, control, &sol);
  st.dp_ms = MsSince(t0);
  st.search_triangles = n * (n - 1) * (n - 2) / 6;
  st.table_bytes = sol.table_bytes;
  st.non_delaunay_triangles = sol.not_preferred;
  r->space_used = SpaceUsed::kAllDelaunayFirst;
  r->solver = HasBiTriangleWeight(weights) ? Solver::kGk2Greedy : Solver::kGk1;
  if (s.code == StatusCode::kNoTriangulation) {
    s.message =
        "no triangulation among all triangles avoids the forbidden chords "
        "and degenerate triangles";
  }
  if (!s.ok()) return s;
  r->triangles.clear();
  for (const Triangle& t : sol.triangles) {
    r->triangles.push_back({loop.ids[t[0]], loop.ids[t[1]], loop.ids[t[2]]});
  }
  return OkStatus();
}

}  // namespace

std::vector<std::vector<int32_t>> ResultLoops(const Result& r) {
  if (r.loop_sizes.empty()) return {r.polygon};
  std::vector<std::vector<int32_t>> loops;
  size_t begin = 0;
  for (int32_t size : r.loop_sizes) {
    const size_t end = std::min(r.polygon.size(), begin + size);
    loops.emplace_back(r.polygon.begin() + begin, r.polygon.begin() + end);
    begin = end;
  }
  return loops;
}

Result Triangulate(const Problem& problem, const Options& options,
                   const Control& control) {
  const auto t_start = Clock::now();
  Result r;
  Report(control, Stage::kValidate, 0);
  r.status = CheckProblem(problem, options);
  if (!r.status.ok()) return r;
  // Everything below works on exactly rescaled coordinates.
  const UnitScale scale = ChooseUnitScale(problem.vertices);
  std::vector<Vec3> work;
  work.reserve(problem.vertices.size());
  for (const Vec3& v : problem.vertices) work.push_back(scale.ToWork(v));
  // Exact unless a coordinate falls below the normal range on the way
  // down: then the predicates would decide another polygon than the
  // caller's.
  for (size_t i = 0; i < work.size(); ++i) {
    if (!(scale.ToCaller(work[i]) == problem.vertices[i])) {
      r.status = InvalidArgument(
          "vertex " + std::to_string(i) + " " + FormatVec(problem.vertices[i]) +
          " has a coordinate too small to keep its precision at the "
          "polygon's scale (more than 2^1022 times smaller than the largest "
          "coordinate, or subnormal); round it to zero");
      return r;
    }
  }
  const PlaneFit fit = FitPlane(work);
  // The fit decides within the tolerance, its rounding included; exactly
  // collinear or planar polygons are so whatever the rounding (at a
  // tolerance of 0 a planar one went on to the 3D Delaunay step: refused by
  // CGAL as coplanar, an abort in TetGen).
  const int dimension = AffineDimension(work);
  PlaneFit line_fit = fit;
  if (dimension <= 1) line_fit.max_line_distance = 0;
  r.status = CheckNotCollinear(
      line_fit, static_cast<int>(problem.vertices.size()), options);
  if (!r.status.ok()) return r;
  r.delaunay = options.delaunay;
  r.planar = dimension == 2 ||
             fit.max_plane_distance <= options.planar_tolerance * fit.diagonal;
  MetricWeights weights = problem.weights;
  if (!HasNonZeroWeight(weights)) weights[Metric::kArea] = 1;
  const MetricWeights work_weights = WorkWeights(weights, scale);

  PolygonLoop loop{std::move(work), problem.normals, {}, {}, {}};
  for (const Vec3& n : problem.edge_face_normals) {
    loop.edge_normals.push_back(Normalized(n));
  }
  loop.ids.resize(problem.vertices.size());
  std::iota(loop.ids.begin(), loop.ids.end(), 0);
  r.stats.validate_ms = MsSince(t_start);

  const bool several = problem.loop_sizes.size() > 1;
  std::shared_ptr<const PreparedSpace> space;
  Status s;
  bool fallback = false;
  if (options.space == SearchSpace::kDelaunayFirst) {
    if (several) {
      s = InvalidArgument(
          "search space 'delaunay_first' takes one loop; this problem has " +
          std::to_string(problem.loop_sizes.size()));
    } else {
      s = SolveDelaunayFirst(fit, r.planar, work_weights, problem, options,
                             control, loop, &r);
    }
  } else if (several) {
    loop.sizes = problem.loop_sizes;
    s = SolveLoops(fit, r.planar, work_weights, problem, options, control,
                   &loop, &r);
  } else {
    const bool bi = HasBiTriangleWeight(weights);
    SpaceCache* cache = control.space_cache;
    if (options.space != SearchSpace::kAll) {
      const std::string key = cache ? SpaceCacheKey(problem, options) : "";
      if (cache) space = cache->Find(key);
      r.stats.cache_hit = space != nullptr;
      if (space != nullptr) {
        r.stats.tetrahedra = space->tetrahedra;
        r.stats.delaunay_triangles = space->delaunay_triangles;
      } else {
        auto fresh = std::make_shared<PreparedSpace>();
        fresh->loop = loop;
        s = PrepareDelaunay(fit, r.planar, cache != nullptr, bi,
                            problem.forbidden_edges, options, control,
                            fresh.get(), &r.stats);
        if (s.ok() && cache) cache->Insert(key, fresh, fresh->Bytes());
        space = std::move(fresh);
      }
      if (s.ok()) s = Solve(*space, work_weights, options, control, &r);
    }
    fallback = options.space == SearchSpace::kAuto &&
               s.code == StatusCode::kNoTriangulation &&
               loop.size() <= options.all_space_max_vertices;
    if (options.space == SearchSpace::kAll || fallback) {
      auto fresh = std::make_shared<PreparedSpace>();
      fresh->loop = loop;
      s = PrepareAll(work_weights, problem.forbidden_edges, options, control,
                     fresh.get(), &r.stats);
      if (s.ok()) s = Solve(*fresh, work_weights, options, control, &r);
      space = std::move(fresh);
    }
  }
  r.status = s;
  // The loop with any inserted vertices; copied once, since a cached space
  // is shared.
  const PolygonLoop& solved = space != nullptr ? space->loop : loop;
  r.stats.n = solved.size();
  // Back in the caller's coordinates: the input's exactly, then inserted
  // ones (the inverse scaling is exact too, unless it ends below the normal
  // range: then the mesh the caller gets is not the one solved).
  r.vertices = problem.vertices;
  for (size_t i = problem.vertices.size(); i < solved.vertices.size(); ++i) {
    r.vertices.push_back(scale.ToCaller(solved.vertices[i]));
    if (r.status.ok() &&
        !(scale.ToWork(r.vertices.back()) == solved.vertices[i])) {
      r.status = InvalidArgument(
          "edge protection inserted vertex " + std::to_string(i) +
          ", which a double cannot hold at the polygon's scale (it falls "
          "below the normal range); scale the polygon up");
      r.triangles.clear();
    }
  }
  r.polygon = solved.ids;
  if (several) r.loop_sizes = solved.sizes;
  for (auto id = static_cast<int32_t>(problem.vertices.size());
       id < static_cast<int32_t>(r.vertices.size()); ++id) {
    r.inserted.push_back(id);
  }
  if (r.status.ok()) {
    Report(control, Stage::kTiling, 1);
    r.metric_costs =
        ToCallerUnits(EvaluateMetrics(solved.vertices, solved.normals,
                                      r.triangles, solved.edge_normals),
                      scale);
    r.total_cost = WeightedTotal(weights, r.metric_costs);
    // Only the weighted metrics count: an unweighted one may overflow in
    // the caller's units (the area, from coordinates near 1e154 on). A
    // weighted one that does makes the total infinite, or NaN when two
    // overflow with opposite signs.
    const bool metrics_finite =
        std::all_of(kAllMetrics.begin(), kAllMetrics.end(), [&](Metric m) {
          return weights[m] == 0 || std::isfinite(r.metric_costs[m]);
        });
    if ((metrics_finite && !std::isfinite(r.total_cost)) ||
        std::isnan(r.total_cost)) {
      r.status = InvalidArgument(
          "the weighted cost overflows a double (the weights times the "
          "metric sums exceed 1.8e308); scale the weights down: only their "
          "ratios matter");
      r.triangles.clear();
    }
    if (options.validate_output || r.space_used == SpaceUsed::kAll ||
        r.space_used == SpaceUsed::kAllDelaunayFirst) {
      // On the work coordinates: the same answer (exact scaling, exact
      // predicates), without extreme magnitudes.
      r.intersecting_pairs =
          CountIntersectingPairs(solved.vertices, r.triangles);
    }
    // The product's promise is an intersection-free result: `auto` never
    // answers OK with a self-intersecting one (an explicit kAll may).
    if (fallback && r.intersecting_pairs > 0) {
      r.status = MakeStatus(
          StatusCode::kNoTriangulation,
          "no intersection-free triangulation found: the polygon has no "
          "Delaunay triangulation, and the optimum over all triangles "
          "self-intersects (" +
              std::to_string(r.intersecting_pairs) +
              " pairs); try protect_edges, or ask for search space 'all' to "
              "get that self-intersecting optimum");
      r.triangles.clear();
    }
  }
  r.stats.total_ms = MsSince(t_start);
  return r;
}

}  // namespace dot
