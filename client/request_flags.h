// SPDX-License-Identifier: AGPL-3.0-or-later
// Flags shared by the subcommands that send polygons: metric weights and
// options, and the connection to the server.
#ifndef DOT_CLIENT_REQUEST_FLAGS_H_
#define DOT_CLIENT_REQUEST_FLAGS_H_

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace CLI {
class App;
}

namespace dot::client {

struct RequestFlags {
  MetricWeights weights;
  std::string space = "auto";
  std::string delaunay;  // "": the server's default
  bool no_cache = false;
  bool protect_edges = false;
  bool validate = false;
  bool keep_loop_directions = false;
  uint32_t time_budget_ms = 0;
  bool omit_input_vertices = true;

  v1::Options ToOptions() const;
};
void AddRequestFlags(CLI::App* cmd, RequestFlags* flags);
// --area, --perimeter, ... bound to `weights`, with a help text per metric
// (in Metric order) under `group`.
void AddWeightFlags(CLI::App* cmd, MetricWeights* weights,
                    const std::string& group,
                    const std::array<std::string, kMetricCount>& help);

struct ConnectionFlags {
  std::string server = "localhost:50051";
  std::string tls_ca;    // enables TLS
  std::string tls_cert;  // client certificate for mutual TLS
  std::string tls_key;
  std::string tls_server_name;  // override the name checked in the cert
  double timeout_s = 120;
};
void AddConnectionFlags(CLI::App* app, ConnectionFlags* flags);

}  // namespace dot::client

#endif  // DOT_CLIENT_REQUEST_FLAGS_H_
