// SPDX-License-Identifier: AGPL-3.0-or-later
// Google Benchmark microbenchmarks of each stage on the paper's curves: the
// Delaunay step (both backends), adjacency, the dynamic programs with
// tiling, validation, and (with the service) wire serialization. The figure
// suite is dot-bench (bench/run-suite.sh).
#include <benchmark/benchmark.h>

#include "dot/dot.h"
#include "search_space/delaunay_cgal.h"
#include "search_space/faces_of_tetrahedra.h"
#include "solve/adjacency.h"
#include "solve/solvers.h"
#ifdef DOT_HAVE_WIRE
#include "wire/wire.h"
#endif

namespace dot {
namespace {

std::vector<Vec3> Monkey(const benchmark::State& state) {
  return MakeCurve(Curve::kMonkey, static_cast<int>(state.range(0)));
}

std::vector<Triangle> MonkeyFaces(const std::vector<Vec3>& points) {
  std::vector<Triangle> faces;
  int64_t tets = 0;
  (void)CgalDelaunayFaces(points, {}, &faces, &tets);
  return faces;
}

void BM_DelaunayTetgen(benchmark::State& state) {
  const auto points = Monkey(state);
  for (auto _ : state) {
    Tetrahedralization t;
    std::vector<Triangle> faces;
    benchmark::DoNotOptimize(TetgenTetrahedralize(points, &t));
    benchmark::DoNotOptimize(FacesOfTetrahedra(t, &faces));
  }
}
void BM_DelaunayCgal(benchmark::State& state) {
  const auto points = Monkey(state);
  for (auto _ : state) benchmark::DoNotOptimize(MonkeyFaces(points));
}
BENCHMARK(BM_DelaunayTetgen)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DelaunayCgal)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);

void BM_Adjacency(benchmark::State& state) {
  const auto points = Monkey(state);
  const auto faces = MonkeyFaces(points);
  for (auto _ : state) {
    state.PauseTiming();
    auto candidates = faces;  // in the backend's order, as a solve gets them
    state.ResumeTiming();
    Adjacency adj;
    benchmark::DoNotOptimize(BuildAdjacency(static_cast<int32_t>(points.size()),
                                            &candidates, {}, &adj));
  }
}
BENCHMARK(BM_Adjacency)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);

// The dynamic program and tiling alone, over a prepared adjacency.
void BM_DynamicProgram(benchmark::State& state, bool bi) {
  const auto points = Monkey(state);
  auto faces = MonkeyFaces(points);
  Adjacency adj;
  (void)BuildAdjacency(static_cast<int32_t>(points.size()), &faces, {}, &adj);
  CandidateWeights w;
  std::vector<Vec3> unit;
  for (const Triangle& f : faces) {
    w.push_back(PerTriangleMetrics(points, {}, f)[Metric::kArea]);
    unit.push_back(UnitNormal(points, f));
  }
  for (auto _ : state) {
    DpSolution sol;
    benchmark::DoNotOptimize(
        bi ? SolveDot2(adj, w, CandidateNormals(unit), {}, {0, 1}, {}, &sol)
           : SolveDot1(adj, w, {}, &sol));
  }
}
BENCHMARK_CAPTURE(BM_DynamicProgram, dot1, false)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DynamicProgram, dot2, true)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);

void Solve(benchmark::State& state, Curve curve, Metric metric) {
  Problem p{MakeCurve(curve, static_cast<int>(state.range(0))), {}, {}, {}, {}};
  p.weights[metric] = 1;
  Stats last;
  for (auto _ : state) {
    const Result r = Triangulate(p);
    last = r.stats;
    benchmark::DoNotOptimize(r.total_cost);
  }
  state.counters["delaunay_ms"] = last.delaunay_ms;
  state.counters["adjacency_ms"] = last.adjacency_ms;
  state.counters["dp_ms"] = last.dp_ms;
  state.counters["tiling_ms"] = last.tiling_ms;
  state.counters["table_MiB"] = last.table_bytes / 1048576.0;
}

void BM_Dot1Monkey(benchmark::State& s) {
  Solve(s, Curve::kMonkey, Metric::kArea);
}
void BM_Dot2Monkey(benchmark::State& s) {
  Solve(s, Curve::kMonkey, Metric::kSquaredDihedral);
}
void BM_Dot2Twist(benchmark::State& s) {
  Solve(s, Curve::kTwist, Metric::kSquaredDihedral);
}
BENCHMARK(BM_Dot1Monkey)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Dot2Monkey)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Dot2Twist)
    ->Arg(251)
    ->Arg(501)
    ->Arg(1001)
    ->Unit(benchmark::kMillisecond);

void BM_Validate(benchmark::State& state) {
  Problem p{MakeCurve(Curve::kMonkey, static_cast<int>(state.range(0))),
            {},
            {},
            {},
            {}};
  const Result r = Triangulate(p);
  for (auto _ : state) {
    benchmark::DoNotOptimize(ValidateMesh(r.vertices, r.polygon, r.triangles));
  }
}
BENCHMARK(BM_Validate)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

#ifdef DOT_HAVE_WIRE
// Result -> summary and mesh chunks -> bytes, as the server sends them.
void BM_Serialize(benchmark::State& state) {
  Problem p{Monkey(state), {}, {}, {}, {}};
  const Result r = Triangulate(p);
  for (auto _ : state) {
    v1::Summary summary;
    wire::FillSummary(r, &summary);
    size_t bytes = summary.ByteSizeLong();
    wire::MeshChunker chunker(r, 0, 1 << 20);
    v1::MeshChunk chunk;
    while (chunker.Next(&chunk)) bytes += chunk.SerializeAsString().size();
    benchmark::DoNotOptimize(bytes);
  }
}
BENCHMARK(BM_Serialize)->Arg(1000)->Arg(100000)->Unit(benchmark::kMillisecond);
#endif

}  // namespace
}  // namespace dot

BENCHMARK_MAIN();
