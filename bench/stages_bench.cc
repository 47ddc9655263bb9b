// SPDX-License-Identifier: AGPL-3.0-or-later
// Google Benchmark microbenchmarks of the pipeline's stages on the paper's
// curves. The full benchmark suite (figures, CGAL comparison) builds on
// these.
#include <benchmark/benchmark.h>

#include "dot/dot.h"

namespace dot {
namespace {

void BM_Tetrahedralize(benchmark::State& state) {
  const auto points =
      MakeCurve(Curve::kMonkey, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    Tetrahedralization t;
    benchmark::DoNotOptimize(TetgenTetrahedralize(points, &t));
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Tetrahedralize)
    ->RangeMultiplier(4)
    ->Range(256, 16384)
    ->Unit(benchmark::kMillisecond);

void Solve(benchmark::State& state, Curve curve, Metric metric) {
  Problem p{MakeCurve(curve, static_cast<int>(state.range(0))), {}, {}};
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
  Problem p{
      MakeCurve(Curve::kMonkey, static_cast<int>(state.range(0))), {}, {}};
  const Result r = Triangulate(p);
  for (auto _ : state) {
    benchmark::DoNotOptimize(ValidateMesh(r.vertices, r.polygon, r.triangles));
  }
}
BENCHMARK(BM_Validate)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dot

BENCHMARK_MAIN();
