// SPDX-License-Identifier: AGPL-3.0-or-later
// The memory budget bounds a request end to end, the Delaunay step
// included: polygons whose tetrahedralization has Theta(n^2) cells are
// stopped at the budget, on CGAL (in this process) and TetGen (in helper
// processes) alike, also two at once, and the memory is given back.
#include <gtest/gtest.h>

#include <fstream>
#include <future>
#include <iostream>
#include <string>

#include "fixtures/service_fixture.h"
#include "remote/grpc_calls.h"

namespace dot {
namespace {

using client::TriangulateRemote;
using testing::CurveRequest;
using testing::Weights;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;  // shadow memory and quarantine distort RSS
#else
constexpr bool kSanitized = false;
#endif

int64_t StatusKib(const std::string& pid, const std::string& field) {
  std::ifstream in("/proc/" + pid + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field + ":", 0) == 0) {
      return std::atoll(line.c_str() + field.size() + 1);
    }
  }
  return -1;
}

void ResetPeak(const std::string& pid) {
  std::ofstream("/proc/" + pid + "/clear_refs") << "5";
}

// Two skew lines, n/2 points each: Theta(n^2) Delaunay tetrahedra.
v1::TriangulateRequest SkewLines(int n) {
  std::vector<Vec3> p;
  for (int i = 0; i < n / 2; ++i) p.push_back({i / double(n), 0, 0});
  for (int i = n / 2 - 1; i >= 0; --i) p.push_back({0.5, i / double(n), 1});
  return wire::MakeRequest("skew", {p, {}}, Weights(Metric::kArea), {});
}

TEST(MemoryBudgetTest, DelaunayStepStaysWithinTheBudget) {
  constexpr int64_t kBudget = int64_t{256} << 20;
  constexpr int64_t kMarginKib = 150 << 10;  // libraries, threads, buffers
  for (DelaunayBackend backend :
       {DelaunayBackend::kCgal, DelaunayBackend::kTetgen}) {
    if (backend == DelaunayBackend::kTetgen &&
        (!TetgenAvailable() || kSanitized)) {
      continue;  // uncapped helpers under ASan
    }
    SCOPED_TRACE(DelaunayBackendName(backend));
    auto config = testing::LoopbackConfig();
    config.pool.threads = 2;
    config.helpers.count = 2;
    config.service.solve.delaunay = backend;
    config.service.solve.memory_budget_bytes = kBudget;
    config.service.malloc_keep_bytes = 64 << 20;
    auto s = testing::StartServer(config);
    const auto warm = CurveRequest(Curve::kMonkey, 50, Weights(Metric::kArea));
    ASSERT_TRUE(TriangulateRemote(*s.stub, warm, {}, 30).status.ok());
    ResetPeak("self");
    const int64_t base_kib = StatusKib("self", "VmRSS");
    std::vector<std::future<grpc::Status>> calls;
    for (const auto& request :
         {CurveRequest(Curve::kMoment, 10000, Weights(Metric::kArea)),
          SkewLines(10000)}) {
      calls.push_back(std::async(std::launch::async, [&s, request] {
        return TriangulateRemote(*s.stub, request, {}, 120).status;
      }));
    }
    for (auto& call : calls) {
      const grpc::Status st = call.get();
      EXPECT_EQ(st.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED)
          << st.error_message();
    }
    const int64_t peak_kib = StatusKib("self", "VmHWM") - base_kib;
    int64_t helpers_kib = 0;
    if (backend == DelaunayBackend::kTetgen) {
      for (pid_t pid : s.server->helpers()->Pids()) {
        helpers_kib += StatusKib(std::to_string(pid), "VmHWM");
      }
    }
    const int64_t after_kib = StatusKib("self", "VmRSS") - base_kib;
    std::cout << DelaunayBackendName(backend)
              << ": two requests at once, budget " << (kBudget >> 20)
              << " MiB each: server peak +" << (peak_kib >> 10)
              << " MiB, helpers' peaks " << (helpers_kib >> 10)
              << " MiB, server after +" << (after_kib >> 10) << " MiB\n";
    if (!kSanitized) {
      EXPECT_LT(peak_kib, 2 * (kBudget >> 10) + kMarginKib);
      EXPECT_LT(helpers_kib, 2 * ((kBudget >> 10) + kMarginKib));
      EXPECT_LT(after_kib, kMarginKib);  // the memory was given back
    }
  }
}

}  // namespace
}  // namespace dot
