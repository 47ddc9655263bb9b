// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-server's configuration: the option structs of its components, each
// the one home of its settings and defaults. AddServerFlags binds every
// flag (with a DOT_* environment fallback) straight to its field, so
// `--help` shows the defaults the structs define and nothing is copied.
#ifndef DOT_SERVER_CONFIG_H_
#define DOT_SERVER_CONFIG_H_

#include <cstdint>
#include <string>
#include <vector>

#include "compute/compute_pool.h"
#include "dot/delaunay_helpers.h"
#include "rpc/service_options.h"
#include "server_metrics.h"

namespace CLI {
class App;
}

namespace dot::server {

struct TlsOptions {
  std::string cert, key;  // PEM; both or neither (then plaintext)
  std::string client_ca;  // PEM; set: clients must present a certificate
};

// The core's helper options, with the flag that raises their memory cap
// named in out-of-memory messages.
inline DelaunayHelperOptions HelperDefaults() {
  DelaunayHelperOptions h;
  h.memory_limit_setting = "dot-server --helper-memory-mb";
  return h;
}

struct ServerConfig {
  std::string listen = "0.0.0.0:50051";
  // A second, plaintext endpoint serving only gRPC health (e.g.
  // 127.0.0.1:50052), for a container health check when the main port
  // speaks TLS; "": none.
  std::string health_listen;
  // Drain and exit when stdin reaches end of file: a parent that starts
  // the server (Blender's "Run Locally") keeps a pipe to it open, so the
  // server ends with its parent however the parent ends.
  bool exit_with_stdin = false;
  ServiceOptions service;
  ComputePoolOptions pool;
  DelaunayHelperOptions helpers = HelperDefaults();
  MetricsOptions metrics;
  TlsOptions tls;
  int64_t cache_bytes = int64_t{256} << 20;  // search-space cache; 0: off
  int drain_seconds = 20;
  int max_connection_age_s = 300;  // 0: never recycle connections
  // Connections left waiting this long in the kernel's accept queue mean
  // gRPC stopped accepting (it does after running out of file
  // descriptors): dot-server then drains and exits 70. 0: no watchdog.
  int listener_patience_s = 20;
  std::string log_level = "info";
  std::string log_format = "text";  // text or json (one object a line)
  // Set by FinalizeConfig: adjustments it made, for the start-up log.
  std::vector<std::string> notes;
};

void AddServerFlags(CLI::App& app, ServerConfig* config);
// Resolves derived defaults (threads, helper count and path), lowers limits
// the rest cannot honour (noted in `notes`), and checks the whole; returns
// an error message, or "" when the configuration is usable.
std::string FinalizeConfig(ServerConfig* config);

}  // namespace dot::server

#endif  // DOT_SERVER_CONFIG_H_
