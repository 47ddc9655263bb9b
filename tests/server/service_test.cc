// SPDX-License-Identifier: AGPL-3.0-or-later
// Integration tests: a real server on loopback, real helper processes.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <random>
#include <set>
#include <thread>

#include "dot/elapsed.h"
#include "fixtures/service_fixture.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "remote/grpc_calls.h"

namespace dot {
namespace {

using client::CallOutcome;
using client::TriangulateRemote;
using testing::CurveRequest;
using testing::StartServer;
using testing::Weights;
using Clock = std::chrono::steady_clock;

// The same problem solved in-process: what the server must return.
Result LocalResult(const v1::TriangulateRequest& request) {
  Problem p;
  Options o;
  EXPECT_TRUE(wire::ProblemFromRequest(request, &p, &o).ok());
  return Triangulate(p, o);
}

void ExpectSameAsLocal(const v1::TriangulateRequest& request,
                       const CallOutcome& out) {
  ASSERT_TRUE(out.status.ok()) << out.status.error_message();
  const Result local = LocalResult(request);
  ASSERT_EQ(out.summary.status(), v1::RESULT_STATUS_OK)
      << out.summary.message();
  EXPECT_EQ(out.mesh.triangles, local.triangles);
  EXPECT_EQ(out.mesh.vertices.size(), local.vertices.size());
  EXPECT_DOUBLE_EQ(out.summary.total_cost(), local.total_cost);
  std::vector<int32_t> loop(local.polygon);
  const MeshReport report =
      ValidateMesh(out.mesh.vertices, loop, out.mesh.triangles);
  EXPECT_TRUE(report.valid()) << report.first_problem;
}

std::vector<Vec3> Input(const v1::TriangulateRequest& r) {
  Problem p;
  Options o;
  EXPECT_TRUE(wire::ProblemFromRequest(r, &p, &o).ok());
  return p.vertices;
}

TEST(ServiceTest, TriangulateWithEveryMetricMix) {
  auto s = StartServer(testing::LoopbackConfig());
  std::vector<MetricWeights> mixes = {
      Weights(Metric::kArea), Weights(Metric::kPerimeter),
      Weights(Metric::kSquaredDihedral), Weights(Metric::kDihedral, -0.5)};
  MetricWeights combo = Weights(Metric::kArea);
  combo[Metric::kSquaredDihedral] = 0.3;
  combo[Metric::kShape] = 0.1;
  mixes.push_back(combo);
  for (Curve c : kPaperCurves) {
    for (const MetricWeights& w : mixes) {
      const auto request = CurveRequest(c, 120, w);
      ExpectSameAsLocal(
          request, TriangulateRemote(*s.stub, request, Input(request), 30));
    }
  }
  // Normal deviation needs normals: a planar disk with normals up.
  PolygonData disk;
  for (int i = 0; i < 40; ++i) {
    const double t = 6.283185307179586 * i / 40;
    disk.vertices.push_back({std::cos(t), std::sin(t), 0.2 * std::sin(3 * t)});
    disk.normals.push_back({0, 0, 1});
  }
  MetricWeights nd = Weights(Metric::kNormalDeviation);
  nd[Metric::kArea] = 1;
  const auto request = wire::MakeRequest("disk", disk, nd, {});
  const CallOutcome out =
      TriangulateRemote(*s.stub, request, disk.vertices, 30);
  ExpectSameAsLocal(request, out);
  EXPECT_GT(out.summary.metric_costs().normal_deviation(), 0);
}

TEST(ServiceTest, ResolvesComeFromTheCacheAndSaySo) {
  auto s = StartServer(testing::LoopbackConfig());
  auto request = CurveRequest(Curve::kTwist, 400, Weights(Metric::kArea));
  const std::vector<Vec3> input = Input(request);
  auto call = [&] { return TriangulateRemote(*s.stub, request, input, 30); };
  const CallOutcome first = call();
  ExpectSameAsLocal(request, first);
  EXPECT_FALSE(first.summary.cache_hit());
  EXPECT_EQ(first.summary.delaunay_backend(), "cgal");
  *request.mutable_weights() = wire::ToWire(Weights(Metric::kSquaredDihedral));
  const CallOutcome second = call();
  ExpectSameAsLocal(request, second);
  EXPECT_TRUE(second.summary.cache_hit());
  EXPECT_EQ(second.summary.stats().delaunay_ms(), 0);

  request.mutable_options()->set_no_cache(true);
  EXPECT_FALSE(call().summary.cache_hit());
  request.mutable_options()->set_no_cache(false);
  if (!TetgenAvailable()) return;
  request.mutable_options()->set_delaunay_backend(v1::DELAUNAY_BACKEND_TETGEN);
  const CallOutcome tetgen = call();
  ExpectSameAsLocal(request, tetgen);
  EXPECT_FALSE(tetgen.summary.cache_hit());  // a different space
  EXPECT_EQ(tetgen.summary.delaunay_backend(), "tetgen");

  request.mutable_options()->set_delaunay_backend(
      static_cast<v1::DelaunayBackend>(7));
  const grpc::Status bad = call().status;
  EXPECT_EQ(bad.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(bad.error_message().find("delaunay_backend 7"), std::string::npos)
      << bad.error_message();
}

TEST(ServiceTest, LargeResultArrivesWholeInSmallChunks) {
  auto config = testing::LoopbackConfig();
  config.service.chunk_bytes = 64 << 10;  // forces dozens of chunks
  auto s = StartServer(config);
  // A client that accepts no message over 256 KiB still gets it all.
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(256 * 1024);
  auto small = v1::Triangulator::NewStub(grpc::CreateCustomChannel(
      s.address, grpc::InsecureChannelCredentials(), args));
  auto request = CurveRequest(Curve::kMonkey, 100000, Weights(Metric::kArea));
  grpc::ClientContext context;
  auto reader = small->Triangulate(&context, request);
  v1::TriangulateResponse msg;
  int chunks = 0;
  wire::MeshAssembler assembler;
  v1::Summary summary;
  while (reader->Read(&msg)) {
    if (msg.has_mesh()) {
      ++chunks;
      EXPECT_LE(msg.ByteSizeLong(), 80u * 1024);
      ASSERT_TRUE(assembler.Add(msg.mesh()).ok());
    }
    if (msg.has_summary()) summary = msg.summary();
  }
  ASSERT_TRUE(reader->Finish().ok());
  EXPECT_GT(chunks, 50);
  MeshData mesh;
  ASSERT_TRUE(assembler.Finish(summary, Input(request), &mesh).ok());
  EXPECT_EQ(mesh.triangles.size(), 99998u);
  EXPECT_EQ(mesh.triangles, LocalResult(request).triangles);
}

TEST(ServiceTest, OmitInputVerticesSendsOnlyInsertedOnes) {
  auto s = StartServer(testing::LoopbackConfig());
  auto request = CurveRequest(Curve::kSpiral, 15, Weights(Metric::kArea));
  request.mutable_options()->set_protect_edges(true);
  request.mutable_options()->set_omit_input_vertices(true);
  const CallOutcome out =
      TriangulateRemote(*s.stub, request, Input(request), 30);
  ASSERT_TRUE(out.status.ok()) << out.status.error_message();
  EXPECT_GT(out.summary.inserted_count(), 0u);
  EXPECT_EQ(out.summary.loop_size(),
            static_cast<int>(out.mesh.vertices.size()));
  ExpectSameAsLocal(request, out);
}

TEST(ServiceTest, BatchAnswersOutOfOrderWithIdsAndIsolatesFailures) {
  auto s = StartServer(testing::LoopbackConfig());
  grpc::ClientContext context;
  auto stream = s.stub->TriangulateBatch(&context);
  std::vector<v1::TriangulateRequest> sent;
  // A slow polygon first, then quick ones, then a bad one.
  sent.push_back(CurveRequest(Curve::kMoment, 1500,
                              Weights(Metric::kSquaredDihedral), "slow"));
  for (int i = 0; i < 6; ++i) {
    sent.push_back(CurveRequest(kPaperCurves[i % 5], 60 + 10 * i,
                                Weights(Metric::kArea),
                                "quick-" + std::to_string(i)));
  }
  v1::TriangulateRequest bad = sent.back();
  bad.set_id("bad");
  bad.mutable_polygon()->add_coordinates(1.0);  // not a multiple of 3
  sent.push_back(bad);
  sent.push_back(
      CurveRequest(Curve::kTrefoil, 80, Weights(Metric::kArea), "knot"));
  for (const auto& r : sent) ASSERT_TRUE(stream->Write(r));
  stream->WritesDone();
  std::map<std::string, wire::MeshAssembler> assemblers;
  std::vector<std::string> order;
  std::map<std::string, v1::TriangulateResponse> last;
  v1::TriangulateResponse msg;
  while (stream->Read(&msg)) {
    if (msg.has_mesh()) {
      ASSERT_TRUE(assemblers[msg.id()].Add(msg.mesh()).ok());
      continue;
    }
    order.push_back(msg.id());
    last[msg.id()] = msg;
    if (msg.has_summary() && msg.summary().status() == v1::RESULT_STATUS_OK) {
      const auto& request =
          *std::find_if(sent.begin(), sent.end(),
                        [&](auto& r) { return r.id() == msg.id(); });
      MeshData mesh;
      ASSERT_TRUE(assemblers[msg.id()]
                      .Finish(msg.summary(), Input(request), &mesh)
                      .ok());
      EXPECT_EQ(mesh.triangles, LocalResult(request).triangles) << msg.id();
    }
  }
  ASSERT_TRUE(stream->Finish().ok());
  ASSERT_EQ(order.size(), sent.size());
  EXPECT_EQ(order.back(), "slow");  // finished last although sent first
  ASSERT_TRUE(last["bad"].has_error());
  EXPECT_EQ(last["bad"].error().code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(last["bad"].error().message().find("expected 3 per vertex"),
            std::string::npos);
  ASSERT_TRUE(last["knot"].has_summary());
  EXPECT_EQ(last["knot"].summary().status(),
            v1::RESULT_STATUS_NO_TRIANGULATION);
  EXPECT_EQ(last["slow"].summary().status(), v1::RESULT_STATUS_OK);
}

TEST(ServiceTest, ErrorsAreStatusCodesNamingTheProblem) {
  auto config = testing::LoopbackConfig();
  config.service.max_vertices = 1000;
  config.service.solve.memory_budget_bytes = 1 << 20;
  auto s = StartServer(config);
  auto call = [&](const v1::TriangulateRequest& r) {
    return TriangulateRemote(*s.stub, r, Input(r), 30).status;
  };
  auto dup = CurveRequest(Curve::kMonkey, 50, Weights(Metric::kArea));
  for (int k = 0; k < 3; ++k) {
    dup.mutable_polygon()->set_coordinates(
        3 * 20 + k, dup.polygon().coordinates(3 * 7 + k));
  }
  grpc::Status st = call(dup);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("vertex 20 repeats vertex 7"),
            std::string::npos)
      << st.error_message();

  st = call(CurveRequest(Curve::kMonkey, 1001, Weights(Metric::kArea)));
  EXPECT_EQ(st.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(st.error_message().find("accepts at most 1000"), std::string::npos);

  st = call(CurveRequest(Curve::kMoment, 900, Weights(Metric::kArea)));
  EXPECT_EQ(st.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(st.error_message().find("exceeds the budget"), std::string::npos);

  // Budgets are unsigned: the largest values mean "the server's limit".
  auto big_budgets = CurveRequest(Curve::kMoment, 900, Weights(Metric::kArea));
  big_budgets.mutable_options()->set_memory_budget_bytes(~uint64_t{0});
  big_budgets.mutable_options()->set_time_budget_ms(~uint32_t{0});
  st = call(big_budgets);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(st.error_message().find("exceeds the budget of 1 MiB"),
            std::string::npos)
      << st.error_message();
  auto quick = CurveRequest(Curve::kMonkey, 30, Weights(Metric::kArea));
  quick.mutable_options()->set_time_budget_ms(~uint32_t{0});
  EXPECT_TRUE(call(quick).ok());

  // Request ids are echoed and logged: long ones are refused.
  auto long_id = CurveRequest(Curve::kMonkey, 30, Weights(Metric::kArea),
                              std::string(257, 'x'));
  st = call(long_id);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("at most 256"), std::string::npos);

  // Deadlines, on a server whose budget does not stop these first.
  auto roomy = StartServer(testing::LoopbackConfig());
  auto slow =
      CurveRequest(Curve::kTwist, 999, Weights(Metric::kSquaredDihedral));
  slow.mutable_options()->set_time_budget_ms(30);
  st = TriangulateRemote(*roomy.stub, slow, Input(slow), 30).status;
  EXPECT_EQ(st.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_NE(st.error_message().find("request's time limit (time_budget_ms 30 "
                                    "ms) passed"),
            std::string::npos)
      << st.error_message();
  EXPECT_NE(st.error_message().find("dotctl --time-budget-ms"),
            std::string::npos);
  const CallOutcome timed_out = TriangulateRemote(
      *roomy.stub, CurveRequest(Curve::kTwist, 999, Weights(Metric::kArea)), {},
      0.03);
  EXPECT_EQ(timed_out.status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);

  // The server's own limit: the message says only its operator can raise
  // it, and with which flag (before: "raise options.time_budget_ms", which
  // the server's limit caps anyway).
  auto tight_config = testing::LoopbackConfig();
  tight_config.service.max_compute_ms = 30;
  auto tight = StartServer(tight_config);
  auto unbudgeted =
      CurveRequest(Curve::kTwist, 999, Weights(Metric::kSquaredDihedral));
  st = TriangulateRemote(*tight.stub, unbudgeted, Input(unbudgeted), 30).status;
  EXPECT_EQ(st.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_NE(st.error_message().find("server's compute time limit (30 ms)"),
            std::string::npos)
      << st.error_message();
  EXPECT_NE(st.error_message().find("dot-server --max-compute-ms"),
            std::string::npos);
}

// A long run cancelled by its client frees the only compute thread at once.
void ExpectCancelFreesTheWorker(const server::ServerConfig& config,
                                const v1::TriangulateRequest& long_request) {
  auto s = StartServer(config);
  grpc::ClientContext context;
  auto reader = s.stub->Triangulate(&context, long_request);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto cancelled_at = Clock::now();
  context.TryCancel();
  v1::TriangulateResponse msg;
  while (reader->Read(&msg)) {
  }
  EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::CANCELLED);
  const auto quick = CurveRequest(Curve::kMonkey, 100, Weights(Metric::kArea));
  const CallOutcome out = TriangulateRemote(*s.stub, quick, Input(quick), 30);
  ASSERT_TRUE(out.status.ok()) << out.status.error_message();
  // The single worker was freed: the quick call ran. How soon is a figure
  // (scripts/stop_latency.sh), not a wall-clock bound on a loaded machine.
  const double freed_ms = MsSince(cancelled_at);
  std::printf(
      "worker free and next call answered %.1f ms after the cancel "
      "(queued %.1f ms)\n",
      freed_ms, out.summary.queue_ms());
}

TEST(ServiceTest, CancelFreesTheWorkerForTheNextRequest) {
  for (DelaunayBackend backend :
       {DelaunayBackend::kCgal, DelaunayBackend::kTetgen}) {
    if (!TetgenAvailable() && backend == DelaunayBackend::kTetgen) continue;
    SCOPED_TRACE(DelaunayBackendName(backend));
    auto config = testing::LoopbackConfig();
    config.pool.threads = 1;
    config.helpers.count = 1;
    config.service.solve.delaunay = backend;
    ExpectCancelFreesTheWorker(
        config,
        CurveRequest(Curve::kTwist, 1501, Weights(Metric::kSquaredDihedral)));
  }
}

// Calls small enough to run on the RPC thread cannot see a cancel until they
// end, so the costly 'all' space (seconds at n = 300) is never run there.
TEST(ServiceTest, SmallAllTrianglesCallIsStillCancellable) {
  auto config = testing::LoopbackConfig();
  config.pool.threads = 1;
  ASSERT_GE(config.service.inline_max_vertices, 300);
  auto request =
      CurveRequest(Curve::kSpiral, 300, Weights(Metric::kSquaredDihedral));
  request.mutable_options()->set_search_space(v1::SEARCH_SPACE_ALL);
  // Run inline, it would hold the thread for its whole ~5 s.
  ExpectCancelFreesTheWorker(config, request);
}

// Each open batch stream is a reactor object, not a thread: many idle
// streams add no threads and little memory to the (in-process) server.
TEST(ServiceTest, IdleBatchStreamsCostNoThreads) {
  auto s = StartServer(testing::LoopbackConfig());
  auto count_threads = [] {
    return std::distance(std::filesystem::directory_iterator("/proc/self/task"),
                         std::filesystem::directory_iterator());
  };
  auto rss_mb = [] {
    std::ifstream in("/proc/self/statm");
    long pages_total = 0, pages_resident = 0;
    in >> pages_total >> pages_resident;
    return static_cast<double>(pages_resident) * ::sysconf(_SC_PAGESIZE) /
           (1 << 20);
  };
  // Warm the connection (its threads start with the first call).
  const auto quick = CurveRequest(Curve::kMonkey, 50, Weights(Metric::kArea));
  ASSERT_TRUE(TriangulateRemote(*s.stub, quick, Input(quick), 30).status.ok());
  const auto threads_before = count_threads();
  const double rss_before = rss_mb();
  constexpr int kStreams = 1000;
  std::vector<std::unique_ptr<grpc::ClientContext>> contexts;
  std::vector<std::unique_ptr<grpc::ClientReaderWriter<
      v1::TriangulateRequest, v1::TriangulateResponse>>>
      streams;
  for (int i = 0; i < kStreams; ++i) {
    contexts.push_back(std::make_unique<grpc::ClientContext>());
    streams.push_back(s.stub->TriangulateBatch(contexts.back().get()));
  }
  // Each stream still works: one polygon over the last one opened.
  ASSERT_TRUE(streams.back()->Write(quick));
  v1::TriangulateResponse msg;
  bool summary = false;
  while (!summary && streams.back()->Read(&msg)) summary = msg.has_summary();
  EXPECT_TRUE(summary);
  const auto threads_after = count_threads();
  const double rss_after = rss_mb();
  std::cout << kStreams << " idle batch streams: threads " << threads_before
            << " -> " << threads_after << ", RSS " << rss_before << " -> "
            << rss_after << " MiB (server and client together)\n";
  EXPECT_LT(threads_after - threads_before, 16);
  EXPECT_LT(rss_after - rss_before, 50);  // client and server together
  for (auto& c : contexts) c->TryCancel();
  for (auto& st : streams) st->Finish();
}

// Streams cancelled at random moments, some while their last polygon is
// being solved: every stream ends, every admitted polygon is answered once
// (in-flight returns to 0), and nothing touches a finished reactor (ASan).
TEST(ServiceTest, BatchStreamsCancelledMidFlightEndCleanly) {
  auto s = StartServer(testing::LoopbackConfig());
  std::mt19937 rng(7);
  for (int i = 0; i < 40; ++i) {
    grpc::ClientContext context;
    auto stream = s.stub->TriangulateBatch(&context);
    for (int k = 0; k < 3; ++k) {
      auto r =
          CurveRequest(Curve::kSpiral, 200 + 50 * k,
                       Weights(Metric::kSquaredDihedral), std::to_string(k));
      if (!stream->Write(r)) break;
    }
    if (i % 2 == 0) stream->WritesDone();
    std::this_thread::sleep_for(std::chrono::microseconds(rng() % 8000));
    context.TryCancel();
    v1::TriangulateResponse msg;
    while (stream->Read(&msg)) {
    }
    const grpc::StatusCode code = stream->Finish().error_code();
    EXPECT_TRUE(code == grpc::StatusCode::CANCELLED ||
                code == grpc::StatusCode::OK)
        << code;
  }
  const auto until = Clock::now() + std::chrono::seconds(10);
  while (s.server->jobs().inflight() > 0 && Clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(s.server->jobs().inflight(), 0);
}

TEST(ServiceTest, OverloadIsRefusedAtOnce) {
  auto config = testing::LoopbackConfig();
  config.pool.threads = 1;
  config.pool.queue_size = 1;
  auto s = StartServer(config);
  auto slow =
      CurveRequest(Curve::kMoment, 1200, Weights(Metric::kSquaredDihedral));
  std::vector<std::future<grpc::Status>> calls;
  for (int i = 0; i < 4; ++i) {
    calls.push_back(std::async(std::launch::async, [&] {
      return TriangulateRemote(*s.stub, slow, Input(slow), 60).status;
    }));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  int ok = 0, exhausted = 0;
  for (auto& f : calls) {
    const grpc::Status st = f.get();
    if (st.ok()) ++ok;
    if (st.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED) {
      ++exhausted;
      EXPECT_NE(st.error_message().find("server at capacity"),
                std::string::npos);
    }
  }
  EXPECT_EQ(ok, 2);  // one running, one queued
  EXPECT_EQ(exhausted, 2);
}

TEST(ServiceTest, DrainGoesNotServingAndFinishesInFlightWork) {
  auto s = StartServer(testing::LoopbackConfig());
  auto health = grpc::health::v1::Health::NewStub(s.channel);
  auto check = [&] {
    grpc::ClientContext c;
    grpc::health::v1::HealthCheckResponse r;
    EXPECT_TRUE(health->Check(&c, {}, &r).ok());
    return r.status();
  };
  EXPECT_EQ(check(), grpc::health::v1::HealthCheckResponse::SERVING);
  auto slow =
      CurveRequest(Curve::kMoment, 1200, Weights(Metric::kSquaredDihedral));
  auto in_flight = std::async(std::launch::async, [&] {
    return TriangulateRemote(*s.stub, slow, Input(slow), 60);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::thread drain([&] { s.server->Drain(std::chrono::seconds(30)); });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(check(), grpc::health::v1::HealthCheckResponse::NOT_SERVING);
  const auto quick = CurveRequest(Curve::kMonkey, 50, Weights(Metric::kArea));
  EXPECT_EQ(
      TriangulateRemote(*s.stub, quick, Input(quick), 5).status.error_code(),
      grpc::StatusCode::UNAVAILABLE);
  const CallOutcome done = in_flight.get();
  EXPECT_TRUE(done.status.ok()) << done.status.error_message();
  EXPECT_EQ(done.summary.status(), v1::RESULT_STATUS_OK);
  drain.join();
}

TEST(ServiceTest, DrainCancelsWorkThatOutlivesTheGracePeriod) {
  auto s = StartServer(testing::LoopbackConfig());
  auto slow =
      CurveRequest(Curve::kTwist, 2001, Weights(Metric::kSquaredDihedral));
  auto in_flight = std::async(std::launch::async, [&] {
    return TriangulateRemote(*s.stub, slow, Input(slow), 60);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const auto t0 = Clock::now();
  s.server->Drain(std::chrono::milliseconds(100));
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 3.0);
  // UNAVAILABLE, not CANCELLED: clients retry it on another replica.
  const grpc::Status status = in_flight.get().status;
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAVAILABLE)
      << status.error_message();
}

TEST(ServiceTest, WithoutHelpersTetgenIsRefusedNotRunInProcess) {
  // Before: --delaunay-helpers 0 ran TetGen in the server's process, and a
  // client asking for it on this polygon aborted the server.
  if (!TetgenAvailable()) GTEST_SKIP() << "built without TetGen";
  auto config = testing::LoopbackConfig();
  config.helpers.count = 0;
  auto s = StartServer(config);
  ASSERT_EQ(s.server->helpers(), nullptr);
  PolygonData rim;
  ASSERT_TRUE(
      ReadPolygonFile(DOT_TEST_DATA_DIR "/tetgen_aborts.xyz", &rim).ok());
  v1::Options options;
  options.set_delaunay_backend(v1::DELAUNAY_BACKEND_TETGEN);
  options.set_search_space(v1::SEARCH_SPACE_DELAUNAY);
  const auto request =
      wire::MakeRequest("rim", rim, Weights(Metric::kArea), options);
  const grpc::Status st =
      TriangulateRemote(*s.stub, request, Input(request), 30).status;
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("--delaunay-helpers is 0"),
            std::string::npos)
      << st.error_message();
  const auto after = CurveRequest(Curve::kMonkey, 200, Weights(Metric::kArea));
  ExpectSameAsLocal(after, TriangulateRemote(*s.stub, after, Input(after), 30));

  // A server whose default is TetGen needs its helpers.
  config.service.solve.delaunay = DelaunayBackend::kTetgen;
  std::string error;
  EXPECT_EQ(server::DotServer::Start(config, &error), nullptr);
  EXPECT_NE(error.find("needs helper processes"), std::string::npos) << error;
}

TEST(ServiceTest, HelperCrashCostsOnlyThatRequest) {
  if (!TetgenAvailable()) GTEST_SKIP() << "built without TetGen";
  auto config = testing::LoopbackConfig();
  config.pool.threads = 1;
  config.helpers.count = 1;
  config.service.solve.delaunay = DelaunayBackend::kTetgen;
  auto s = StartServer(config);
  const auto warm = CurveRequest(Curve::kMonkey, 50, Weights(Metric::kArea));
  ASSERT_TRUE(TriangulateRemote(*s.stub, warm, Input(warm), 30).status.ok());
  const auto pids = s.server->helpers()->Pids();
  ASSERT_EQ(pids.size(), 1u);
  auto big = CurveRequest(Curve::kMoment, 3000, Weights(Metric::kArea));
  auto victim = std::async(std::launch::async, [&] {
    return TriangulateRemote(*s.stub, big, Input(big), 60);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // in TetGen
  ASSERT_EQ(::kill(pids[0], SIGSEGV), 0);
  const CallOutcome crashed = victim.get();
  EXPECT_EQ(crashed.status.error_code(), grpc::StatusCode::INTERNAL);
  // "crashed on this input (signal 11, ...)"; under ASan, whose handler
  // takes the signal, "exited with code 1 while working on this input".
  EXPECT_NE(crashed.status.error_message().find("on this input"),
            std::string::npos)
      << crashed.status.error_message();
  const auto after = CurveRequest(Curve::kMobius, 300, Weights(Metric::kArea));
  ExpectSameAsLocal(after, TriangulateRemote(*s.stub, after, Input(after), 30));
  EXPECT_EQ(s.server->helpers()->starts(), 2);
}

// A helper killed while idle is replaced before the next request uses it;
// one killed mid-request is reported as killed, not as crashing on it.
TEST(ServiceTest, HelperKilledWhileIdleIsReplacedSilently) {
  if (!TetgenAvailable()) GTEST_SKIP() << "built without TetGen";
  auto config = testing::LoopbackConfig();
  config.pool.threads = 1;
  config.helpers.count = 1;
  config.service.solve.delaunay = DelaunayBackend::kTetgen;
  auto s = StartServer(config);
  const auto warm = CurveRequest(Curve::kMonkey, 50, Weights(Metric::kArea));
  ASSERT_TRUE(TriangulateRemote(*s.stub, warm, Input(warm), 30).status.ok());
  auto pids = s.server->helpers()->Pids();
  ASSERT_EQ(pids.size(), 1u);
  ASSERT_EQ(::kill(pids[0], SIGKILL), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto next = CurveRequest(Curve::kMobius, 300, Weights(Metric::kArea));
  ExpectSameAsLocal(next, TriangulateRemote(*s.stub, next, Input(next), 30));
  EXPECT_EQ(s.server->helpers()->starts(), 2);

  pids = s.server->helpers()->Pids();
  ASSERT_EQ(pids.size(), 1u);
  auto big = CurveRequest(Curve::kMoment, 3000, Weights(Metric::kArea));
  auto victim = std::async(std::launch::async, [&] {
    return TriangulateRemote(*s.stub, big, Input(big), 60);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // in TetGen
  ASSERT_EQ(::kill(pids[0], SIGKILL), 0);
  const grpc::Status killed = victim.get().status;
  EXPECT_EQ(killed.error_code(), grpc::StatusCode::INTERNAL);
  EXPECT_NE(killed.error_message().find("was killed (SIGKILL"),
            std::string::npos)
      << killed.error_message();
}

TEST(ServiceTest, HelperMemoryCapFailsOnlyTheBigRequest) {
  if (!TetgenAvailable()) GTEST_SKIP() << "built without TetGen";
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan builds cannot cap a helper's address space";
#endif
  auto config = testing::LoopbackConfig();
  config.pool.threads = 1;
  config.helpers.count = 1;
  config.service.solve.delaunay = DelaunayBackend::kTetgen;
  config.helpers.memory_limit_bytes = int64_t{100} << 20;
  auto s = StartServer(config);
  // About 2 million tetrahedra: far more than 100 MiB inside TetGen.
  const auto big = CurveRequest(Curve::kMoment, 2000, Weights(Metric::kArea));
  const grpc::Status st =
      TriangulateRemote(*s.stub, big, Input(big), 60).status;
  EXPECT_EQ(st.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(st.error_message().find("ran out of memory"), std::string::npos)
      << st.error_message();
  const auto small = CurveRequest(Curve::kMonkey, 200, Weights(Metric::kArea));
  ExpectSameAsLocal(small, TriangulateRemote(*s.stub, small, Input(small), 30));
}

TEST(ServiceTest, HelperThatCannotHoldItsInputSaysSo) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan builds cannot cap a helper's address space";
#endif
  // Before: the helper died on an uncaught bad_alloc (SIGABRT, reported as
  // a crash on this input) or was left with the request half read.
  auto config = testing::LoopbackConfig();
  config.helpers.count = 1;
  config.helpers.memory_limit_bytes = int64_t{20} << 20;
  auto s = StartServer(config);
  std::vector<Vec3> points(2'000'000);  // 48 MB
  for (size_t i = 0; i < points.size(); ++i) {
    points[i] = {double(i % 1000), double(i / 1000 % 1000), double(i % 7)};
  }
  Tetrahedralization out;
  const Status st = s.server->helpers()->Tetrahedralize(
      points, &out, nullptr,
      std::chrono::steady_clock::now() + std::chrono::seconds(60), 0);
  EXPECT_EQ(st.code, StatusCode::kResourceExhausted) << st.message;
  EXPECT_NE(st.message.find("ran out of memory holding its input"),
            std::string::npos)
      << st.message;
  EXPECT_NE(st.message.find("--helper-memory-mb"), std::string::npos)
      << st.message;
  // The next request gets a fresh helper.
  const std::vector<Vec3> cube = {
      {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  const Status next = s.server->helpers()->Tetrahedralize(
      cube, &out, nullptr,
      std::chrono::steady_clock::now() + std::chrono::seconds(60), 0);
  if (TetgenAvailable()) {
    EXPECT_TRUE(next.ok()) << next.message;
    EXPECT_FALSE(out.tets.empty());
  }
}

TEST(ServiceTest, ConcurrentResultsEqualSequentialOnes) {
  auto config = testing::LoopbackConfig();
  config.pool.threads = 4;
  config.pool.queue_size = 32;  // room for every request at once
  auto s = StartServer(config);
  std::vector<v1::TriangulateRequest> requests;
  for (int i = 0; i < 24; ++i) {
    MetricWeights w = Weights(i % 2 ? Metric::kArea : Metric::kSquaredDihedral);
    requests.push_back(CurveRequest(kPaperCurves[i % 5], 100 + 37 * i, w,
                                    "c" + std::to_string(i)));
  }
  std::vector<std::future<CallOutcome>> futures;
  for (const auto& r : requests) {
    futures.push_back(std::async(std::launch::async, [&s, &r] {
      return TriangulateRemote(*s.stub, r, Input(r), 60);
    }));
  }
  for (size_t i = 0; i < requests.size(); ++i) {
    ExpectSameAsLocal(requests[i], futures[i].get());
  }
}

TEST(ServiceTest, ServerInfoAndSource) {
  const std::string archive =
      (std::filesystem::temp_directory_path() / "dot-test-source.tar.gz")
          .string();
  {
    std::ofstream out(archive, std::ios::binary);
    out << std::string(600 * 1024, 'x');
  }
  auto config = testing::LoopbackConfig();
  config.service.source_archive = archive;
  config.service.source_url = "https://example.org/dot";
  auto s = StartServer(config);
  grpc::ClientContext c1;
  v1::ServerInfo info;
  ASSERT_TRUE(s.stub->GetServerInfo(&c1, {}, &info).ok());
  EXPECT_EQ(info.license(), "AGPL-3.0-or-later");
  EXPECT_EQ(info.source_url(), "https://example.org/dot");
  EXPECT_EQ(info.limits().compute_threads(), 2u);
  // The advertised limit fits in one request message (24 bytes a vertex).
  EXPECT_LE(uint64_t{info.limits().max_vertices()} * 24,
            info.limits().max_message_bytes());
  EXPECT_GT(info.limits().max_vertices(), 600000u);
  EXPECT_EQ(info.limits().cache_bytes(), uint64_t{256} << 20);
  EXPECT_NE(info.backends(0).find("cgal"), std::string::npos);
  EXPECT_FALSE(info.version().empty());
  grpc::ClientContext c2;
  auto reader = s.stub->GetSource(&c2, {});
  v1::SourceChunk chunk;
  size_t bytes = 0;
  while (reader->Read(&chunk)) bytes += chunk.data().size();
  EXPECT_TRUE(reader->Finish().ok());
  EXPECT_EQ(bytes, 600u * 1024);
  std::filesystem::remove(archive);
}

}  // namespace
}  // namespace dot
