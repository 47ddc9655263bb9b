// SPDX-License-Identifier: AGPL-3.0-or-later
// Large inputs on small stacks, cancellation, deadlines and progress.
#include <gtest/gtest.h>
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <vector>

#include "dot/dot.h"
#include "fixtures/checks.h"

namespace dot {
namespace {

using Clock = std::chrono::steady_clock;

// Runs `fn` on a thread with a stack of `bytes`.
template <typename Fn>
void RunWithStack(size_t bytes, Fn fn) {
  pthread_attr_t attr;
  ASSERT_EQ(pthread_attr_init(&attr), 0);
  ASSERT_EQ(pthread_attr_setstacksize(&attr, bytes), 0);
  pthread_t thread;
  auto trampoline = [](void* arg) -> void* {
    (*static_cast<Fn*>(arg))();
    return nullptr;
  };
  ASSERT_EQ(pthread_create(&thread, &attr, trampoline, &fn), 0);
  pthread_join(thread, nullptr);
  pthread_attr_destroy(&attr);
}

TEST(ScaleTest, HundredThousandVerticesOnOneMebibyteStack) {
  for (bool bi : {false, true}) {
    Problem p{MakeCurve(Curve::kMonkey, 100000), {}, {}, {}, {}};
    p.weights[bi ? Metric::kSquaredDihedral : Metric::kArea] = 1;
    Result r;
    RunWithStack(1 << 20, [&] { r = Triangulate(p); });
    ASSERT_TRUE(r.status.ok()) << r.status.message;
    EXPECT_EQ(r.triangles.size(), 100000u - 2);
    const MeshReport report = ValidateMesh(r.vertices, r.polygon, r.triangles);
    EXPECT_TRUE(report.valid()) << report.first_problem;
    EXPECT_EQ(report.intersecting_pairs, 0);
  }
}

// Cancels a long DOT2 run when it reaches `stage` and returns the delay
// between the cancel and Triangulate's return.
double CancelLatencyMs(Stage stage, StatusCode* code) {
  Problem p{MakeCurve(Curve::kTwist, 1501), {}, {}, {}, {}};
  p.weights[Metric::kSquaredDihedral] = 1;
  std::atomic<bool> cancel{false};
  Clock::time_point cancelled_at;
  Control control;
  control.cancel = &cancel;
  control.progress = [&](Stage s, double fraction) {
    // In the Delaunay step, cancel once CGAL is well into its insertions.
    const bool midway = stage != Stage::kDelaunay || fraction > 0.2;
    if (s == stage && midway && !cancel) {
      cancelled_at = Clock::now();
      cancel = true;
    }
  };
  const Result r = Triangulate(p, {}, control);
  *code = r.status.code;
  return MsSince(cancelled_at);
}

// The stop latency is a figure, printed here and measured by
// scripts/stop_latency.sh, not asserted: a wall-clock bound failed on a
// loaded 2-core machine (175 ms for a 100 ms bound).
TEST(CancelTest, CancelStopsLongDot2RunInEveryStage) {
  for (Stage stage :
       {Stage::kDelaunay, Stage::kAdjacency, Stage::kDynamicProgram}) {
    StatusCode code;
    const double ms = CancelLatencyMs(stage, &code);
    EXPECT_EQ(code, StatusCode::kCancelled) << StageName(stage);
    std::printf("cancel in %s: stopped %.1f ms later\n",
                std::string(StageName(stage)).c_str(), ms);
  }
}

TEST(CancelTest, DeadlineStopsTheRun) {
  Problem p{MakeCurve(Curve::kTwist, 1501), {}, {}, {}, {}};
  p.weights[Metric::kSquaredDihedral] = 1;
  Control control;
  control.deadline = Clock::now() + std::chrono::milliseconds(30);
  const Result r = Triangulate(p, {}, control);
  EXPECT_EQ(r.status.code, StatusCode::kDeadlineExceeded);
  EXPECT_NE(r.status.message.find("deadline exceeded"), std::string::npos);
}

TEST(ProgressTest, ReportsStagesInOrder) {
  Problem p{MakeCurve(Curve::kMobius, 400), {}, {}, {}, {}};
  p.weights[Metric::kSquaredDihedral] = 1;
  std::vector<Stage> stages;
  Control control;
  control.progress = [&](Stage s, double f) {
    EXPECT_GE(f, 0);
    EXPECT_LE(f, 1);
    if (stages.empty() || stages.back() != s) stages.push_back(s);
  };
  ASSERT_TRUE(Triangulate(p, {}, control).status.ok());
  const std::vector<Stage> expected = {Stage::kValidate, Stage::kDelaunay,
                                       Stage::kAdjacency,
                                       Stage::kDynamicProgram, Stage::kTiling};
  EXPECT_EQ(stages, expected);
}

TEST(BackendTest, InjectedTetrahedralizationServesTheTetgenBackend) {
  DOT_SKIP_WITHOUT_TETGEN();
  Problem p{MakeCurve(Curve::kSpiral, 200), {}, {}, {}, {}};
  int calls = 0;
  Control control;
  control.tetrahedralize = [&](const std::vector<Vec3>&, Tetrahedralization*) {
    ++calls;
    return MakeStatus(StatusCode::kInternal, "helper process died");
  };
  Options tetgen;
  tetgen.delaunay = DelaunayBackend::kTetgen;
  const Result r = Triangulate(p, tetgen, control);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(r.status.code, StatusCode::kInternal);
  EXPECT_EQ(r.status.message, "helper process died");
}

}  // namespace
}  // namespace dot
