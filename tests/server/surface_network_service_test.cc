// SPDX-License-Identifier: AGPL-3.0-or-later
// SurfaceNetwork over a real server on loopback: a network streamed in
// (many messages), the surface back as computed locally, bad networks
// refused by name with the server up, limits, and a cancel mid-surface.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "dot/dot.h"
#include "fixtures/cut_mesh.h"
#include "fixtures/service_fixture.h"
#include "remote/grpc_calls.h"
#include "wire/surface_wire.h"

namespace dot {
namespace {

using testing::LoopbackConfig;
using testing::StartServer;

// The rims of 150 patches cut from a mesh: ~400 curves.
CurveNetwork CutNetworkOf(const std::string& mesh_name, int patches) {
  return testing::CutMesh(mesh_name, patches, 1, 1).network;
}

TEST(SurfaceNetworkServiceTest, StreamsInAndComesBackAsComputedLocally) {
  auto config = LoopbackConfig();
  config.service.chunk_bytes = 16 << 10;  // many response chunks
  auto s = StartServer(config);
  const CurveNetwork net = CutNetworkOf("homer.off", 150);
  const PolygonSoup soup = wire::SoupFromNetwork(net);
  size_t requests = 0;
  wire::SurfaceRequestWriter writer("homer", {}, soup, 4 << 10);
  for (v1::SurfaceNetworkRequest r; writer.Next(&r);) ++requests;
  EXPECT_GT(requests, 3u);
  // The client's own chunking is 1 MiB: send small slices by hand.
  grpc::ClientContext context;
  auto stream = s.stub->SurfaceNetwork(&context);
  wire::SurfaceRequestWriter small("homer", {}, soup, 4 << 10);
  for (v1::SurfaceNetworkRequest r; small.Next(&r);) {
    ASSERT_TRUE(stream->Write(r));
  }
  stream->WritesDone();
  int progress = 0, meshes = 0;
  v1::SurfaceReport report;
  for (v1::SurfaceNetworkResponse r; stream->Read(&r);) {
    progress += r.has_progress();
    meshes += r.has_mesh();
    if (r.has_report()) report = r.report();
  }
  ASSERT_TRUE(stream->Finish().ok());
  EXPECT_GT(progress, 0);
  EXPECT_GT(meshes, 1);
  EXPECT_TRUE(report.closed());
  EXPECT_EQ(report.input_vertices(), net.vertices.size());

  const client::SurfaceOutcome remote =
      client::SurfaceRemote(*s.stub, "homer", {}, net, 60);
  ASSERT_TRUE(remote.status.ok()) << remote.status.error_message();
  const client::SurfaceOutcome local = client::SurfaceLocal({}, net);
  ASSERT_TRUE(local.status.ok()) << local.status.error_message();
  EXPECT_EQ(remote.mesh.triangles, local.mesh.triangles);
  ASSERT_EQ(remote.mesh.vertices.size(), local.mesh.vertices.size());
  for (size_t v = 0; v < local.mesh.vertices.size(); ++v) {
    ASSERT_EQ(remote.mesh.vertices[v], local.mesh.vertices[v]) << v;
  }
  EXPECT_EQ(remote.report.surfaced(), local.report.surfaced());
  // The network's vertices come first, exactly.
  for (size_t v = 0; v < net.vertices.size(); ++v) {
    ASSERT_EQ(remote.mesh.vertices[v], net.vertices[v]) << v;
  }
}

TEST(SurfaceNetworkServiceTest, BadNetworksAreRefusedNamingTheProblem) {
  auto s = StartServer(LoopbackConfig());
  CurveNetwork net = CubeNetwork(2);
  net.polylines.push_back({0, 99});
  auto r = client::SurfaceRemote(*s.stub, "bad", {}, net, 30);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("99"), std::string::npos)
      << r.status.error_message();
  // Crossing curves.
  CurveNetwork crossing;
  crossing.vertices = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  crossing.polylines = {{0, 1}, {2, 3}};
  r = client::SurfaceRemote(*s.stub, "crossing", {}, crossing, 30);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("cross"), std::string::npos);
  // A polyline of one point, and a bad option.
  v1::SurfaceNetworkRequest one;
  one.mutable_network()->add_vertices(0);
  one.mutable_network()->add_vertices(0);
  one.mutable_network()->add_vertices(0);
  one.mutable_network()->add_triangles(0);
  one.mutable_network()->add_face_sizes(1);
  {
    grpc::ClientContext context;
    auto stream = s.stub->SurfaceNetwork(&context);
    stream->Write(one);
    stream->WritesDone();
    for (v1::SurfaceNetworkResponse m; stream->Read(&m);) {
    }
    const grpc::Status st = stream->Finish();
    EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(st.error_message().find("polyline of 1 points"),
              std::string::npos)
        << st.error_message();
  }
  v1::SurfaceOptions o;
  o.set_density(-1);
  r = client::SurfaceRemote(*s.stub, "density", o, CubeNetwork(2), 30);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  o = {};
  o.set_islands(static_cast<v1::NetworkIslands>(7));  // a newer client's
  r = client::SurfaceRemote(*s.stub, "islands", o, CubeNetwork(2), 30);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("unknown islands mode 7"),
            std::string::npos)
      << r.status.error_message();
  // Still serving.
  r = client::SurfaceRemote(*s.stub, "after", {}, CubeNetwork(2), 30);
  EXPECT_TRUE(r.status.ok()) << r.status.error_message();
  EXPECT_TRUE(r.report.closed());
}

TEST(SurfaceNetworkServiceTest, LimitsTimeBudgetAndCancel) {
  auto config = LoopbackConfig();
  config.service.fill_max_vertices = 100;
  auto s = StartServer(config);
  auto r = client::SurfaceRemote(*s.stub, "big", {}, CubeNetwork(40), 30);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(r.status.error_message().find("more than 100 vertices"),
            std::string::npos)
      << r.status.error_message();

  auto roomy = StartServer(LoopbackConfig());
  const CurveNetwork net = CutNetworkOf("armadillo.off", 200);
  v1::SurfaceOptions budget;
  budget.set_time_budget_ms(1);
  r = client::SurfaceRemote(*roomy.stub, "budget", budget, net, 60);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);

  // Cancelled by the client mid-surface: the server stops and stays up.
  grpc::ClientContext context;
  auto stream = roomy.stub->SurfaceNetwork(&context);
  const PolygonSoup soup = wire::SoupFromNetwork(net);
  wire::SurfaceRequestWriter writer("c", {}, soup, 1 << 20);
  for (v1::SurfaceNetworkRequest m; writer.Next(&m);) {
    ASSERT_TRUE(stream->Write(m));
  }
  stream->WritesDone();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  context.TryCancel();
  for (v1::SurfaceNetworkResponse m; stream->Read(&m);) {
  }
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::CANCELLED);
  r = client::SurfaceRemote(*roomy.stub, "after", {}, CubeNetwork(3), 30);
  EXPECT_TRUE(r.status.ok()) << r.status.error_message();
}

}  // namespace
}  // namespace dot
