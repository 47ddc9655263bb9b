// SPDX-License-Identifier: AGPL-3.0-or-later
// A real dot-server in this process on an ephemeral loopback port, with its
// TetGen helpers as real child processes, and a client channel to it.
#ifndef DOT_TESTS_SERVICE_FIXTURE_H_
#define DOT_TESTS_SERVICE_FIXTURE_H_

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "dot/dot.h"
#include "dot/v1/triangulation.grpc.pb.h"
#include "dot_server.h"
#include "wire/wire.h"

namespace dot::testing {

inline server::ServerConfig LoopbackConfig() {
  server::ServerConfig c;
  c.listen = "127.0.0.1:0";
  c.pool.threads = 2;
  c.pool.queue_size = 16;
  c.metrics.port = 0;
  c.helpers.executable = DOT_HELPER_PATH;
  c.service.source_archive = "";
  c.log_level = "warn";
  return c;
}

struct RunningServer {
  std::unique_ptr<server::DotServer> server;
  std::shared_ptr<grpc::Channel> channel;
  std::unique_ptr<v1::Triangulator::Stub> stub;
  std::string address;
};

inline RunningServer StartServer(const server::ServerConfig& config) {
  RunningServer s;
  std::string error;
  s.server = server::DotServer::Start(config, &error);
  EXPECT_TRUE(s.server) << error;
  if (!s.server) return s;
  s.address = "127.0.0.1:" + std::to_string(s.server->port());
  s.channel =
      grpc::CreateChannel(s.address, grpc::InsecureChannelCredentials());
  s.stub = v1::Triangulator::NewStub(s.channel);
  return s;
}

inline v1::TriangulateRequest CurveRequest(Curve curve, int n,
                                           const MetricWeights& w,
                                           const std::string& id = "r") {
  return wire::MakeRequest(id, {MakeCurve(curve, n), {}}, w, {});
}

inline MetricWeights Weights(Metric m, double value = 1) {
  MetricWeights w;
  w[m] = value;
  return w;
}

}  // namespace dot::testing

#endif  // DOT_TESTS_SERVICE_FIXTURE_H_
