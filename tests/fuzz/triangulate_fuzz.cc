// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: dot::Triangulate on tiny polygons (4 to 10 vertices)
// decoded from the input, with random coordinates (small integers, the same
// at an extreme power-of-two scale or offset, dyadic fractions, raw bits),
// normals, weights (bi-triangle ones included), sometimes split into two
// loops bounding one surface, and options (search space, backend, edge
// protection, output validation, planarity tolerance, loop reorientation).
//
// Oracle, checked with the project's exact validator (dot/validate.h):
//  - an OK result is a disk whose boundary is the polygon (inserted vertices
//    in place), or for two loops a sphere with two holes bounded by them
//    (a loop reversed only when allowed, and then reported), consistently
//    oriented so that each loop runs i -> i+1 as the result lists it, the
//    input's vertices returned unchanged; intersection-free unless the
//    search space was explicitly kAll, whose intersecting pairs must then be
//    counted right; its total cost is finite when its weighted metrics
//    are (metrics may overflow in the caller's units), and no cost is NaN;
//  - a failure is a known non-OK code with a message;
//  - progress fractions stay in [0, 1];
//  - solved again through a SpaceCache (the second call served from it),
//    an OK answer is the same triangles at the same cost.
// A violated oracle abort()s, which libFuzzer reports as a crash. TetGen
// runs in a helper process, as dot-server runs it (tetgen_child.h).
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "dot/dot.h"
#include "tetgen_child.h"

namespace {

// What is being solved, printed when the oracle fails.
const dot::Problem* g_problem = nullptr;
const dot::Options* g_options = nullptr;

void PrintInput() {
  if (g_problem == nullptr || g_options == nullptr) return;
  std::fprintf(stderr, "polygon (x y z [nx ny nz]):\n");
  for (size_t i = 0; i < g_problem->vertices.size(); ++i) {
    const dot::Vec3& p = g_problem->vertices[i];
    std::fprintf(stderr, "  %.17g %.17g %.17g", p.x, p.y, p.z);
    if (!g_problem->normals.empty()) {
      const dot::Vec3& n = g_problem->normals[i];
      std::fprintf(stderr, "  %g %g %g", n.x, n.y, n.z);
    }
    std::fprintf(stderr, "\n");
  }
  std::fprintf(stderr, "weights:");
  for (dot::Metric m : dot::kAllMetrics) {
    std::fprintf(stderr, " %s=%.17g", std::string(dot::MetricName(m)).c_str(),
                 g_problem->weights[m]);
  }
  std::fprintf(
      stderr,
      "\noptions: space=%s delaunay=%s protect_edges=%d "
      "validate_output=%d planar_tolerance=%g reorient_loops=%d loops:",
      std::string(dot::SearchSpaceName(g_options->space)).c_str(),
      std::string(dot::DelaunayBackendName(g_options->delaunay)).c_str(),
      g_options->protect_edges, g_options->validate_output,
      g_options->planar_tolerance, g_options->reorient_loops);
  for (int32_t size : g_problem->loop_sizes) std::fprintf(stderr, " %d", size);
  std::fprintf(stderr, "\n");
}

[[noreturn]] void Fail(const std::string& what, const dot::Result& r) {
  std::fprintf(stderr,
               "ORACLE FAILED: %s (status %s: %s; space %s, solver %s, %zu "
               "triangles, total cost %.17g)\n",
               what.c_str(),
               std::string(dot::StatusCodeName(r.status.code)).c_str(),
               r.status.message.c_str(),
               std::string(dot::SpaceUsedName(r.space_used)).c_str(),
               std::string(dot::SolverName(r.solver)).c_str(),
               r.triangles.size(), r.total_cost);
  std::fprintf(stderr, "metric costs:");
  for (dot::Metric m : dot::kAllMetrics) {
    std::fprintf(stderr, " %s=%.17g", std::string(dot::MetricName(m)).c_str(),
                 r.metric_costs[m]);
  }
  std::fprintf(stderr, "\n");
  PrintInput();
  std::abort();
}

double RawDouble(FuzzedDataProvider& in) {
  const uint64_t bits = in.ConsumeIntegral<uint64_t>();
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

double SmallInt(FuzzedDataProvider& in, int bound) {
  return in.ConsumeIntegralInRange<int>(-bound, bound);
}

double Weight(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 7)) {
    case 4:
    case 5:
      return SmallInt(in, 3);
    case 6:
      return std::ldexp(SmallInt(in, 3), in.ConsumeIntegralInRange(-60, 60));
    case 7:
      return RawDouble(in);
    default:
      return 0;
  }
}

std::vector<dot::Vec3> Vertices(FuzzedDataProvider& in, int n) {
  const int mode = in.ConsumeIntegralInRange(0, 4);
  const int exponent = in.ConsumeIntegralInRange(-1074, 1020);
  const double offset =
      std::ldexp(SmallInt(in, 3), in.ConsumeIntegralInRange(0, 60));
  auto coordinate = [&]() -> double {
    switch (mode) {
      case 0:  // small integers
        return SmallInt(in, 3);
      case 1:  // the same at any scale: the unit scaling is exact
        return std::ldexp(SmallInt(in, 3), exponent);
      case 2:  // dyadic fractions: nearly degenerate configurations
        return SmallInt(in, 3) + in.ConsumeIntegralInRange(-8, 8) / 256.0;
      case 3:  // small integers far from the origin
        return offset + SmallInt(in, 3);
      default:  // anything, non-finite included
        return RawDouble(in);
    }
  };
  std::vector<dot::Vec3> v(n);
  for (dot::Vec3& p : v) {
    p.x = coordinate();
    p.y = coordinate();
    p.z = coordinate();
  }
  return v;
}

bool SameBits(const dot::Vec3& a, const dot::Vec3& b) {
  return std::memcmp(&a, &b, sizeof(dot::Vec3)) == 0;
}

void CheckOk(const dot::Problem& problem, const dot::Options& options,
             const dot::Result& r) {
  const auto n = static_cast<int32_t>(problem.vertices.size());
  if (r.triangles.empty()) Fail("OK without triangles", r);
  if (r.vertices.size() < problem.vertices.size()) Fail("vertices lost", r);
  for (int32_t i = 0; i < n; ++i) {
    if (!SameBits(r.vertices[i], problem.vertices[i])) {
      Fail("input vertex " + std::to_string(i) + " changed", r);
    }
  }
  // The loops: the input's vertices in order (a reversed loop backwards
  // from its first), inserted ones between them.
  if (r.polygon.size() != r.vertices.size()) Fail("loop size", r);
  if (r.inserted.size() != r.vertices.size() - problem.vertices.size()) {
    Fail("inserted count", r);
  }
  if (!options.protect_edges && !r.inserted.empty()) {
    Fail("vertices inserted without protect_edges", r);
  }
  const std::vector<int32_t> input_sizes =
      problem.loop_sizes.empty() ? std::vector<int32_t>{n} : problem.loop_sizes;
  const std::vector<int32_t> output_sizes =
      problem.loop_sizes.empty()
          ? std::vector<int32_t>{static_cast<int32_t>(r.polygon.size())}
          : r.loop_sizes;
  if (output_sizes.size() != input_sizes.size()) Fail("loop count", r);
  if (!options.reorient_loops && !r.reversed_loops.empty()) {
    Fail("a loop reversed with reorient_loops off", r);
  }
  std::vector<std::vector<int32_t>> loops;
  int32_t input_begin = 0;
  size_t at = 0;
  for (size_t l = 0; l < output_sizes.size(); ++l) {
    if (at + output_sizes[l] > r.polygon.size()) Fail("loop sizes", r);
    loops.emplace_back(r.polygon.begin() + at,
                       r.polygon.begin() + at + output_sizes[l]);
    at += output_sizes[l];
    const bool reversed =
        std::count(r.reversed_loops.begin(), r.reversed_loops.end(),
                   static_cast<int32_t>(l)) > 0;
    const int32_t size = input_sizes[l];
    int32_t k = 0;
    for (int32_t id : loops.back()) {
      if (id < 0 || id >= static_cast<int32_t>(r.vertices.size())) {
        Fail("loop index out of range", r);
      }
      if (id >= n) continue;
      const int32_t want = input_begin + (reversed ? (size - k) % size : k);
      if (k >= size || id != want) Fail("loop out of order", r);
      ++k;
    }
    if (k != size) Fail("loop misses input vertices", r);
    input_begin += size;
  }
  if (at != r.polygon.size()) Fail("loop sizes", r);

  // Edge-manifold, genus 0, bounded by the loops; intersections separately.
  const dot::MeshReport report =
      dot::ValidateSurface(r.vertices, loops, r.triangles, false);
  if (!report.valid()) Fail("invalid mesh: " + report.first_problem, r);
  const int64_t pairs = dot::CountIntersectingPairs(r.vertices, r.triangles);
  if (options.space == dot::SearchSpace::kAll ||
      options.space == dot::SearchSpace::kDelaunayFirst) {
    if (r.intersecting_pairs != pairs) {
      Fail("reported " + std::to_string(r.intersecting_pairs) +
               " intersecting pairs, the validator counts " +
               std::to_string(pairs),
           r);
    }
  } else {
    if (pairs != 0) {
      Fail(std::to_string(pairs) + " intersecting pairs in an OK result", r);
    }
    if (r.intersecting_pairs > 0 ||
        (options.validate_output && r.intersecting_pairs != 0)) {
      Fail("intersecting_pairs " + std::to_string(r.intersecting_pairs), r);
    }
  }
  // Oriented so that each loop runs i -> i+1 as listed: every loop edge is
  // a triangle side in that direction.
  for (const std::vector<int32_t>& loop : loops) {
    const size_t m = loop.size();
    for (size_t i = 0; i < m; ++i) {
      const int32_t a = loop[i], b = loop[(i + 1) % m];
      const bool found = std::any_of(r.triangles.begin(), r.triangles.end(),
                                     [a, b](const dot::Triangle& t) {
                                       return (t[0] == a && t[1] == b) ||
                                              (t[1] == a && t[2] == b) ||
                                              (t[2] == a && t[0] == b);
                                     });
      if (!found) {
        Fail("loop edge " + std::to_string(a) + "->" + std::to_string(b) +
                 " is no triangle side in that direction",
             r);
      }
    }
  }
  // Costs are in the caller's units, where a metric may overflow (the area
  // of a polygon spanning 1e200); but when every weighted one is finite, so
  // is the total, or the call refuses the weights.
  dot::MetricWeights weights = problem.weights;
  if (!dot::HasNonZeroWeight(weights)) weights[dot::Metric::kArea] = 1;
  bool weighted_finite = true;
  for (dot::Metric m : dot::kAllMetrics) {
    if (std::isnan(r.metric_costs[m])) Fail("NaN metric cost", r);
    weighted_finite &= weights[m] == 0 || std::isfinite(r.metric_costs[m]);
  }
  if (std::isnan(r.total_cost)) Fail("NaN total cost", r);
  if (weighted_finite && !std::isfinite(r.total_cost)) {
    Fail("non-finite total cost of finite weighted metrics", r);
  }
}

void CheckFailure(const dot::Result& r) {
  switch (r.status.code) {
    case dot::StatusCode::kNoTriangulation:
    case dot::StatusCode::kInvalidArgument:
    case dot::StatusCode::kResourceExhausted:
    case dot::StatusCode::kCancelled:
    case dot::StatusCode::kDeadlineExceeded:
    case dot::StatusCode::kInternal:
      break;
    default:
      Fail("unknown status code", r);
  }
  if (r.status.message.empty()) Fail("failure without a message", r);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  const int n = in.ConsumeIntegralInRange(4, 10);
  dot::Problem problem;
  problem.vertices = Vertices(in, n);
  // Sometimes two loops bounding one surface (3 or more vertices each).
  if (n >= 6 && in.ConsumeIntegralInRange(0, 2) == 0) {
    const int first = in.ConsumeIntegralInRange(3, n - 3);
    problem.loop_sizes = {first, n - first};
  }
  if (in.ConsumeIntegralInRange(0, 2) == 0) {
    problem.normals.resize(n);
    for (dot::Vec3& v : problem.normals) {
      v = {SmallInt(in, 2), SmallInt(in, 2), SmallInt(in, 2)};
    }
  }
  for (dot::Metric m : dot::kAllMetrics) problem.weights[m] = Weight(in);

  dot::Options options;
  options.space =
      static_cast<dot::SearchSpace>(in.ConsumeIntegralInRange(0, 3));
  options.protect_edges = in.ConsumeBool();
  options.validate_output = in.ConsumeBool();
  if (dot::TetgenAvailable() && in.ConsumeIntegralInRange(0, 3) == 0) {
    options.delaunay = dot::DelaunayBackend::kTetgen;
  }
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 1:
      options.planar_tolerance = 0;
      break;
    case 2:
      options.planar_tolerance = 1e-2;
      break;
    default:
      break;  // the default, 1e-6
  }
  options.max_inserted_vertices = 64;
  options.reorient_loops = in.ConsumeBool();
  const bool via_cache = in.ConsumeIntegralInRange(0, 3) == 0;

  g_problem = &problem;
  g_options = &options;
  dot::Control control;
  control.deadline = std::chrono::steady_clock::now() + std::chrono::seconds(4);
  control.progress = [](dot::Stage, double fraction) {
    if (!(fraction >= 0 && fraction <= 1)) {
      std::fprintf(stderr, "ORACLE FAILED: progress fraction %g\n", fraction);
      PrintInput();
      std::abort();
    }
  };
  dot::SpaceCache cache(int64_t{64} << 20);
  if (via_cache) control.space_cache = &cache;
  // TetGen in a helper process, as dot-server runs it: TetGen
  // 1.5.0 aborts on some degenerate point sets (see tetgen_child.h).
  control.tetrahedralize = dot::fuzz::TetgenInChild;

  dot::Result r = dot::Triangulate(problem, options, control);
  // DOT_FUZZ_PRINT=1 (running one input): what was solved, and the answer.
  static const bool print = std::getenv("DOT_FUZZ_PRINT") != nullptr;
  if (print) {
    PrintInput();
    std::fprintf(stderr, "-> %s: %s (%zu triangles, %zu inserted)\n",
                 std::string(dot::StatusCodeName(r.status.code)).c_str(),
                 r.status.message.c_str(), r.triangles.size(),
                 r.inserted.size());
  }
  if (r.status.ok()) {
    CheckOk(problem, options, r);
  } else {
    CheckFailure(r);
  }
  if (via_cache) {
    const dot::Result again = dot::Triangulate(problem, options, control);
    if (again.status.ok()) {
      CheckOk(problem, options, again);
    } else {
      CheckFailure(again);
    }
    const auto timed_out = [](const dot::Result& x) {
      return x.status.code == dot::StatusCode::kDeadlineExceeded;
    };
    if (!timed_out(r) && !timed_out(again)) {
      if (again.status.code != r.status.code) {
        Fail("from the cache: status " +
                 std::string(dot::StatusCodeName(again.status.code)) +
                 ", first " + std::string(dot::StatusCodeName(r.status.code)),
             again);
      }
      if (r.status.ok() && (again.triangles != r.triangles ||
                            again.total_cost != r.total_cost)) {
        Fail("from the cache: other triangles or cost", again);
      }
    }
  }
  return 0;
}
