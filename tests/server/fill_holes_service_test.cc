// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles over a real server on loopback: the mesh streamed in and out
// (a million faces), bad meshes answered INVALID_ARGUMENT with the server
// staying up, cancel in the middle of a fill.
#include <google/protobuf/unknown_field_set.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <future>
#include <thread>

#include "fixtures/meshes.h"
#include "fixtures/service_fixture.h"
#include "remote/grpc_calls.h"
#include "wire/fill_wire.h"

namespace dot {
namespace {

using testing::LoopbackConfig;
using testing::StartServer;

// A torus of nu x nv quads with `holes` holes of 120 faces cut out of it.
MeshData HoleyTorus(int nu, int nv, int holes) {
  return testing::HoleyTorus(nu, nv, holes, 120);
}

TEST(FillHolesServiceTest, AMillionFacesStreamInAndOutAsFilledLocally) {
  auto config = LoopbackConfig();
  config.service.chunk_bytes = 256 << 10;  // many response chunks too
  auto s = StartServer(config);
  const MeshData m = HoleyTorus(1000, 500, 6);
  ASSERT_GT(m.triangles.size(), 990000u);
  const PolygonSoup soup = ToSoup(m);
  v1::FillOptions options;
  size_t requests = 0;
  wire::FillRequestWriter writer("big", options, soup, 1 << 20);
  for (v1::FillHolesRequest r; writer.Next(&r);) ++requests;
  EXPECT_GT(requests, 10u);
  const auto t0 = std::chrono::steady_clock::now();
  const client::FillOutcome remote =
      client::FillRemote(*s.stub, "big", options, soup, 300);
  ASSERT_TRUE(remote.status.ok()) << remote.status.error_message();
  const double remote_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
          .count();
  const client::FillOutcome local = client::FillLocal("big", options, soup);
  ASSERT_TRUE(local.status.ok()) << local.status.error_message();
  std::printf("1M faces, 6 holes: remote %.2f s, local %.2f s\n", remote_s,
              local.latency_ms / 1000);
  EXPECT_EQ(remote.report.filled(), 6);
  EXPECT_TRUE(remote.report.closed());
  EXPECT_EQ(remote.mesh.triangles, local.mesh.triangles);
  ASSERT_EQ(remote.mesh.vertices.size(), local.mesh.vertices.size());
  for (size_t v = 0; v < local.mesh.vertices.size(); ++v) {
    ASSERT_EQ(remote.mesh.vertices[v], local.mesh.vertices[v]) << v;
  }
  EXPECT_EQ(remote.report.holes_size(), 6);
}

grpc::Status SendRaw(v1::Triangulator::Stub& stub,
                     const std::vector<v1::FillHolesRequest>& messages) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::seconds(30));
  auto stream = stub.FillHoles(&context);
  for (const auto& m : messages) {
    if (!stream->Write(m)) break;
  }
  stream->WritesDone();
  v1::FillHolesResponse r;
  while (stream->Read(&r)) {
  }
  return stream->Finish();
}

v1::FillHolesRequest Message(std::vector<double> vertices,
                             std::vector<uint32_t> faces) {
  v1::FillHolesRequest m;
  for (double x : vertices) m.mutable_mesh()->add_vertices(x);
  for (uint32_t f : faces) m.mutable_mesh()->add_triangles(f);
  return m;
}

TEST(FillHolesServiceTest, BadMeshesAreRefusedNamingTheProblem) {
  auto s = StartServer(LoopbackConfig());
  const std::vector<double> tri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  struct Case {
    std::vector<v1::FillHolesRequest> messages;
    const char* expected;
  };
  v1::FillHolesRequest nan = Message({0, 0, 0, NAN, 0, 0, 0, 1, 0}, {0, 1, 2});
  v1::FillHolesRequest fin =
      Message({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1},
              {0, 1, 2, 1, 0, 3, 0, 1, 4});
  v1::FillHolesRequest late_options = Message({}, {0, 1, 2});
  late_options.set_id("late");
  v1::FillHolesRequest polygons = Message(tri, {0, 1, 2});
  polygons.mutable_mesh()->add_face_sizes(4);
  v1::FillHolesRequest stage = Message(tri, {0, 1, 2});
  stage.mutable_options()->set_fairing_continuity(5);
  const std::vector<Case> cases = {
      {{Message(tri, {0, 1, 9})}, "face 0 has vertex index 9"},
      {{Message({0, 0, 0, 1}, {})}, "not a multiple of 3"},
      {{Message(tri, {0, 1})}, "not a multiple of 3"},
      {{nan}, "vertex 1 has a non-finite coordinate"},
      {{fin}, "shared by 3 faces"},
      {{Message(tri, {}), late_options}, "belong in the first message"},
      {{polygons}, "face_sizes add up to 4 but 3"},
      {{stage}, "fairing_continuity must be 0, 1 or 2"},
      {{Message(tri, {})}, "the mesh has no faces"},
      {{}, "no mesh was sent"},
  };
  for (const Case& c : cases) {
    const grpc::Status st = SendRaw(*s.stub, c.messages);
    EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
        << c.expected << ": " << st.error_message();
    EXPECT_NE(st.error_message().find(c.expected), std::string::npos)
        << "got: " << st.error_message() << "\nexpected: " << c.expected;
  }
  // Still up and right.
  const MeshData m = HoleyTorus(40, 20, 2);
  const auto ok = client::FillRemote(*s.stub, "after", {}, ToSoup(m), 60);
  ASSERT_TRUE(ok.status.ok()) << ok.status.error_message();
  EXPECT_EQ(ok.report.filled(), 2);
}

// FILL_ANSWER_PATCHES: only what is new comes back (several messages for
// a patch larger than a chunk), in the ids as sent, equal to the local
// answer; loops_through names the holes to fill.
TEST(FillHolesServiceTest, PatchesOfTheNamedLoopsComeBackAsComputedLocally) {
  auto config = LoopbackConfig();
  config.service.chunk_bytes = 1024;  // patches continue over messages
  auto s = StartServer(config);
  const MeshData m = HoleyTorus(200, 100, 4);
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 4u);
  v1::FillOptions options;
  options.set_answer(v1::FILL_ANSWER_PATCHES);
  options.add_loops_through(static_cast<uint32_t>(loops[0].vertices[0]));
  options.add_loops_through(static_cast<uint32_t>(loops[2].vertices[7]));
  const PolygonSoup soup = ToSoup(m);
  const auto remote = client::FillRemote(*s.stub, "p", options, soup, 120);
  ASSERT_TRUE(remote.status.ok()) << remote.status.error_message();
  const auto local = client::FillLocal("p", options, soup);
  ASSERT_TRUE(local.status.ok()) << local.status.error_message();
  EXPECT_TRUE(remote.mesh.vertices.empty());  // no whole mesh
  EXPECT_EQ(remote.report.filled(), 2);
  ASSERT_EQ(remote.patches.size(), 2u);
  ASSERT_EQ(local.patches.size(), 2u);
  int32_t next = static_cast<int32_t>(m.vertices.size());
  for (size_t k = 0; k < 2; ++k) {
    const SentPatch& r = remote.patches[k];
    EXPECT_EQ(r.hole, k == 0 ? 0 : 2);
    EXPECT_EQ(r.first_vertex, next);
    next += static_cast<int32_t>(r.new_vertices.size());
    EXPECT_EQ(r.hole, local.patches[k].hole);
    EXPECT_EQ(r.faces, local.patches[k].faces);
    EXPECT_EQ(r.replaced_faces, local.patches[k].replaced_faces);
    ASSERT_EQ(r.new_vertices.size(), local.patches[k].new_vertices.size());
    for (size_t v = 0; v < r.new_vertices.size(); ++v) {
      EXPECT_EQ(r.new_vertices[v], local.patches[k].new_vertices[v]);
    }
  }
  for (const v1::HoleReport& h : remote.report.holes()) {
    EXPECT_EQ(h.status(), h.id() == 0 || h.id() == 2 ? v1::HOLE_STATUS_FILLED
                                                     : v1::HOLE_STATUS_SKIPPED);
  }
}

// Before dot.v1 revision 2 the mesh came in fields 3-5 of the request: an
// old client is told, not answered with an empty mesh.
TEST(FillHolesServiceTest, AnUploadInTheOldFieldsIsRefusedByName) {
  auto s = StartServer(LoopbackConfig());
  v1::FillHolesRequest old;
  old.GetReflection()->MutableUnknownFields(&old)->AddLengthDelimited(
      3, std::string(72, '\0'));
  const grpc::Status st = SendRaw(*s.stub, {old});
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("revision 2"), std::string::npos)
      << st.error_message();
  // Slices out of order are named too.
  v1::FillHolesRequest first = Message({0, 0, 0, 1, 0, 0, 0, 1, 0}, {});
  v1::FillHolesRequest gap = Message({0, 0, 1}, {});
  gap.mutable_mesh()->set_first_vertex(7);
  const grpc::Status order = SendRaw(*s.stub, {first, gap});
  EXPECT_NE(order.error_message().find("starts at vertex 7 but 3 vertices"),
            std::string::npos)
      << order.error_message();
}

TEST(FillHolesServiceTest, LimitsAndCancel) {
  auto config = LoopbackConfig();
  config.service.fill_max_faces = 1000;
  auto s = StartServer(config);
  const MeshData big = HoleyTorus(100, 50, 3);
  auto st = client::FillRemote(*s.stub, "big", {}, ToSoup(big), 60).status;
  EXPECT_EQ(st.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(st.error_message().find("more than 1000 faces"), std::string::npos)
      << st.error_message();

  // Cancelled by the client mid-fill: the server stops and stays up.
  auto roomy = StartServer(LoopbackConfig());
  const MeshData m = HoleyTorus(600, 300, 6);
  const PolygonSoup soup = ToSoup(m);
  grpc::ClientContext context;
  auto stream = roomy.stub->FillHoles(&context);
  wire::FillRequestWriter writer("c", {}, soup, 1 << 20);
  for (v1::FillHolesRequest msg; writer.Next(&msg);) {
    ASSERT_TRUE(stream->Write(msg));
  }
  stream->WritesDone();
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto t0 = std::chrono::steady_clock::now();
  context.TryCancel();
  v1::FillHolesResponse r;
  while (stream->Read(&r)) {
  }
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                .count(),
            5.0);
  const auto after = client::FillRemote(*roomy.stub, "after", {},
                                        ToSoup(HoleyTorus(40, 20, 1)), 60);
  EXPECT_TRUE(after.status.ok()) << after.status.error_message();
}

// A strip around the polygon in `xyz_path`: its inner border is exactly the
// polygon, the outer one the polygon scaled by 2 about its centroid.
MeshData StripAroundPolygon(const std::string& xyz_path) {
  std::ifstream in(xyz_path);
  std::vector<Vec3> rim;
  double x, y, z;
  while (in >> x >> y >> z) rim.push_back({x, y, z});
  Vec3 c{0, 0, 0};
  for (const Vec3& p : rim) c = c + p;
  c = (1.0 / static_cast<double>(rim.size())) * c;
  MeshData m;
  m.vertices = rim;
  for (const Vec3& p : rim) m.vertices.push_back(2.0 * p - c);
  const auto k = static_cast<int32_t>(rim.size());
  for (int32_t i = 0; i < k; ++i) {
    const int32_t j = (i + 1) % k;
    m.triangles.push_back({i, k + i, k + j});
    m.triangles.push_back({i, k + j, j});
  }
  return m;
}

TEST(FillHolesServiceTest, TetgenAbortOnAHoleRimFailsTheCallNotTheServer) {
  // Before: FillHoles ran TetGen in the server's process, and TetGen 1.5's
  // assertion on this rim aborted the whole server.
  auto config = LoopbackConfig();
  config.service.solve.delaunay = DelaunayBackend::kTetgen;
  auto s = StartServer(config);
  ASSERT_FALSE(config.helpers.executable.empty());
  const MeshData strip =
      StripAroundPolygon(DOT_TEST_DATA_DIR "/tetgen_aborts.xyz");
  v1::FillOptions options;
  options.set_no_repair(true);
  options.set_stage(v1::FILL_STAGE_TRIANGULATE);
  const auto outcome =
      client::FillRemote(*s.stub, "rim", options, ToSoup(strip), 60);
  // The hole TetGen could not tetrahedralize is reported, not filled.
  if (outcome.status.ok()) {
    EXPECT_LT(outcome.report.filled(), outcome.report.loops());
    bool named = false;
    for (const auto& h : outcome.report.holes()) {
      named |= h.reason().find("helper") != std::string::npos;
    }
    EXPECT_TRUE(named) << "no hole names the helper's failure";
  } else {
    EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INTERNAL)
        << outcome.status.error_message();
  }
  const auto after = client::FillRemote(*s.stub, "after", {},
                                        ToSoup(HoleyTorus(40, 20, 1)), 60);
  EXPECT_TRUE(after.status.ok()) << after.status.error_message();
}

TEST(FillHolesServiceTest, LargeFairingSystemsAreSolvedInAHelper) {
  // Before: fairing's sparse LU ran in the server's process, where a cancel
  // or deadline could not stop it (0.6 s for a hole of 512 boundary
  // vertices, minutes for larger ones). Now the helper solves it, with the
  // answer of the in-process solve.
  auto config = LoopbackConfig();
  config.helpers.count = 1;
  auto s = StartServer(config);
  const MeshData m = testing::SphereWithCapCut(120, 240, 0.6);
  const auto remote = client::FillRemote(*s.stub, "cap", {}, ToSoup(m), 60);
  ASSERT_TRUE(remote.status.ok()) << remote.status.error_message();
  ASSERT_EQ(remote.report.holes_size(), 1);
  EXPECT_TRUE(remote.report.holes(0).faired())
      << remote.report.holes(0).reason();
  EXPECT_GT(remote.report.holes(0).refined_vertices(), kSolveSparseMinUnknowns);
  EXPECT_EQ(s.server->helpers()->starts(), 1);  // CGAL's Delaunay: fairing
  const client::FillOutcome local = client::FillLocal("cap", {}, ToSoup(m));
  ASSERT_TRUE(local.status.ok()) << local.status.error_message();
  EXPECT_EQ(remote.mesh.triangles, local.mesh.triangles);
  ASSERT_EQ(remote.mesh.vertices.size(), local.mesh.vertices.size());
  for (size_t v = 0; v < local.mesh.vertices.size(); ++v) {
    ASSERT_LT(Distance(remote.mesh.vertices[v], local.mesh.vertices[v]), 1e-9)
        << v;
  }
}

TEST(FillHolesServiceTest, HelperOutOfMemoryIsReportedAsSuch) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan builds cannot cap a helper's address space";
#endif
  // Before: a fairing solve over the helpers' memory cap was reported as
  // "the helper answered 0 values for a solution of ..." (the reply was
  // read before its status).
  auto config = LoopbackConfig();
  config.helpers.count = 1;
  config.helpers.memory_limit_bytes = int64_t{20} << 20;
  auto s = StartServer(config);
  const MeshData m = testing::SphereWithCapCut(120, 240, 0.6);
  const auto remote = client::FillRemote(*s.stub, "cap", {}, ToSoup(m), 60);
  ASSERT_TRUE(remote.status.ok()) << remote.status.error_message();
  ASSERT_EQ(remote.report.holes_size(), 1);
  EXPECT_FALSE(remote.report.holes(0).faired());
  EXPECT_NE(remote.report.holes(0).reason().find("out of memory"),
            std::string::npos)
      << remote.report.holes(0).reason();
}

TEST(FillHolesServiceTest, FillMemoryIsChargedAsTheMeshArrives) {
  // Before: uploads were charged to no budget (70 streams that never
  // half-closed took a server from 72 MB to 5.2 GB).
  auto config = LoopbackConfig();
  const MeshData big = HoleyTorus(100, 50, 2);
  const MeshData small = HoleyTorus(20, 10, 1);
  config.service.fill_memory_bytes =
      server::FillMemoryBytes(static_cast<int64_t>(small.vertices.size()),
                              static_cast<int64_t>(small.triangles.size())) *
      2;
  auto s = StartServer(config);
  const auto refused = client::FillRemote(*s.stub, "big", {}, ToSoup(big), 60);
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(refused.status.error_message().find("memory for FillHoles calls"),
            std::string::npos)
      << refused.status.error_message();
  // The charge is given back: a mesh that fits is filled, twice.
  for (int i = 0; i < 2; ++i) {
    const auto ok = client::FillRemote(*s.stub, "small", {}, ToSoup(small), 60);
    EXPECT_TRUE(ok.status.ok()) << ok.status.error_message();
  }
  // GetServerInfo advertises the FillHoles limits.
  grpc::ClientContext c;
  v1::ServerInfo info;
  ASSERT_TRUE(s.stub->GetServerInfo(&c, {}, &info).ok());
  EXPECT_EQ(info.limits().fill_memory_bytes(),
            static_cast<uint64_t>(config.service.fill_memory_bytes));
  EXPECT_EQ(info.limits().fill_max_faces(),
            static_cast<uint64_t>(config.service.fill_max_faces));
  EXPECT_EQ(info.limits().fill_max_vertices(),
            static_cast<uint64_t>(config.service.fill_max_vertices));
}

TEST(FillHolesServiceTest, StoppedCallsAreAnsweredAndCountedByTheirReason) {
  // Before: every stop was logged CANCELLED "the client went away".
  auto s = StartServer(LoopbackConfig());
  // Seconds of upload and fill: both stops below come well before the end.
  const PolygonSoup soup = ToSoup(HoleyTorus(1000, 500, 6));
  // The client's deadline passes.
  const auto late = client::FillRemote(*s.stub, "late", {}, soup, 0.5);
  EXPECT_EQ(late.status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  // The request's own budget passes.
  v1::FillOptions budget;
  budget.set_time_budget_ms(100);
  const auto limited = client::FillRemote(*s.stub, "budget", budget, soup, 60);
  EXPECT_EQ(limited.status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_NE(limited.status.error_message().find("time limit"),
            std::string::npos)
      << limited.status.error_message();
  // Metrics are counted when the server answers, just after the client
  // sees the status: wait for them (a liveness bound, not a timing test).
  const std::string want_deadline =
      "dot_requests_stopped_total{reason=\"client_deadline\",rpc="
      "\"FillHoles\"} 1";
  const std::string want_budget =
      "dot_requests_stopped_total{reason=\"server_budget\",rpc="
      "\"FillHoles\"} 1";
  std::string scraped;
  for (int i = 0; i < 600; ++i) {
    scraped = s.server->metrics().Scrape();
    if (scraped.find(want_deadline) != std::string::npos &&
        scraped.find(want_budget) != std::string::npos) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_NE(scraped.find(want_deadline), std::string::npos) << scraped;
  EXPECT_NE(scraped.find(want_budget), std::string::npos) << scraped;
}

TEST(FillHolesServiceTest, ADrainMidFillAnswersTheHolesFinishedThenStops) {
  auto s = StartServer(LoopbackConfig());
  const MeshData m = testing::HoleyTorus(600, 300, 80, 1000);
  ASSERT_FALSE(m.triangles.empty());
  std::promise<void> holes_under_way;
  bool signalled = false;
  client::FillOutcome o;
  std::thread call([&] {
    o = client::FillRemote(
        *s.stub, "drained", {}, ToSoup(m), 120, [&](const v1::FillProgress& p) {
          if (!signalled && p.phase() == v1::FILL_PHASE_HOLES &&
              p.holes_done() > 0) {
            signalled = true;
            holes_under_way.set_value();
          }
        });
    if (!signalled) holes_under_way.set_value();  // ends the wait below
  });
  holes_under_way.get_future().wait();
  s.server->Drain(std::chrono::milliseconds(0));
  call.join();
  ASSERT_TRUE(signalled) << "the fill ended before a hole was reported";
  EXPECT_EQ(o.status.error_code(), grpc::StatusCode::UNAVAILABLE)
      << o.status.error_message();
  ASSERT_TRUE(o.partial) << o.status.error_message();
  const v1::FillReport& r = o.report;
  EXPECT_GE(r.filled(), 1u);
  EXPECT_GE(r.stopped(), 1u);
  EXPECT_EQ(r.filled() + r.stopped() + r.unfilled(), r.loops());
  // What came back is exactly a fill of the finished holes alone (each
  // hole's patch depends on nothing else), which the core's tests hold to
  // every promise; and its new faces intersect nothing.
  FillOptions finished;
  for (const v1::HoleReport& h : r.holes()) {
    if (h.status() == v1::HOLE_STATUS_FILLED) {
      finished.selection.ids.push_back(h.id());
    } else {
      EXPECT_EQ(h.status(), v1::HOLE_STATUS_STOPPED) << h.reason();
      EXPECT_TRUE(h.reason().rfind("not started: ", 0) == 0 ||
                  h.reason().rfind("stopped: ", 0) == 0)
          << h.reason();
    }
  }
  const FillResult alone = FillHoles(m, finished);
  ASSERT_TRUE(alone.status.ok()) << alone.status.message;
  EXPECT_EQ(o.mesh.vertices, alone.mesh.vertices);
  EXPECT_EQ(o.mesh.triangles, alone.mesh.triangles);
  std::vector<Triangle> new_first(o.mesh.triangles.begin() + m.triangles.size(),
                                  o.mesh.triangles.end());
  const size_t fresh = new_first.size();
  new_first.insert(new_first.end(), m.triangles.begin(), m.triangles.end());
  EXPECT_EQ(CountIntersectingPairs(o.mesh.vertices, new_first, fresh), 0);
}

}  // namespace
}  // namespace dot
