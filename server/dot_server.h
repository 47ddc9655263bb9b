// SPDX-License-Identifier: AGPL-3.0-or-later
// A running dot server: gRPC (Triangulator, health, reflection), the compute
// pool, Delaunay helpers and metrics, wired from a ServerConfig. Used by
// main() and, in-process on loopback, by the integration tests.
#ifndef DOT_SERVER_DOT_SERVER_H_
#define DOT_SERVER_DOT_SERVER_H_

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>

#include "compute/compute_pool.h"
#include "config.h"
#include "dot/delaunay_helpers.h"
#include "rpc/job.h"
#include "rpc/triangulator_service.h"
#include "server_metrics.h"

namespace dot::server {

class DotServer {
 public:
  // Null with `error` set when the configuration or a port is unusable.
  // The server keeps its copy of `config`; its components refer to it.
  static std::unique_ptr<DotServer> Start(ServerConfig config,
                                          std::string* error);
  ~DotServer();

  int port() const { return port_; }
  // The plaintext health-only port (ServerConfig::health_listen); 0: none.
  int health_port() const { return health_port_; }
  // Graceful stop: health NOT_SERVING, new requests refused, in-flight work
  // given 80% of `grace` to finish, then stopped (a stopped fill answers
  // the holes it finished); the gRPC server shut down once answers are
  // sent or `grace` is over (at least 2 s after the stop).
  void Drain(std::chrono::milliseconds grace);

  JobRunner& jobs() { return *jobs_; }
  ServerMetrics& metrics() { return *metrics_; }
  DelaunayHelperPool* helpers() { return helpers_.get(); }

 private:
  DotServer() = default;
  // Health of both endpoints, for the server ("") and the service name.
  void SetServing(bool serving);
  ServerConfig config_;
  std::unique_ptr<ServerMetrics> metrics_;
  std::unique_ptr<DelaunayHelperPool> helpers_;
  std::unique_ptr<ComputePool> pool_;
  std::unique_ptr<SpaceCache> cache_;
  std::unique_ptr<JobRunner> jobs_;
  std::unique_ptr<TriangulatorService> service_;
  std::unique_ptr<grpc::Server> server_;
  std::unique_ptr<grpc::Server> health_server_;  // health only, plaintext
  int port_ = 0, health_port_ = 0;
  std::atomic<bool> drained_{false};
};

}  // namespace dot::server

#endif  // DOT_SERVER_DOT_SERVER_H_
