// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-server's configuration: every setting is a flag with an environment
// variable fallback (DOT_*), listed with its default by --help.
#ifndef DOT_SERVER_CONFIG_H_
#define DOT_SERVER_CONFIG_H_

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace dot::server {

struct ServerConfig {
  std::string listen = "0.0.0.0:50051";
  int threads = 0;      // 0: number of cores
  int queue_size = 64;  // requests waiting for a thread
  int max_vertices = 1000000;
  int max_compute_ms = 60000;
  int64_t memory_budget_mb = 2048;        // per request, DP tables
  int all_space_max_vertices = 40;        // auto fallback to 'all'
  std::string delaunay_backend = "cgal";  // default of requests
  int64_t cache_mb = 256;                 // search-space cache; 0: off
  int64_t malloc_keep_mb = 512;   // freed memory kept for reuse; 0: glibc's
  int inline_max_vertices = 500;  // run small calls on the RPC thread
  int delaunay_helpers = -1;      // -1: one per thread; 0: in-process TetGen
  std::string helper_path;        // default: next to the server binary
  int64_t helper_memory_mb = 4096;
  int metrics_port = 9090;  // 0: off
  std::string metrics_bind = "0.0.0.0";
  std::string tls_cert, tls_key, tls_client_ca;
  int drain_seconds = 20;
  int max_message_mb = 16;
  int chunk_kb = 1024;  // mesh chunk size
  int max_connection_age_s = 300;
  std::string log_level = "info";
  std::string source_archive = "/usr/share/dot/dot-source.tar.gz";
  std::string source_url;
};

void AddServerFlags(CLI::App& app, ServerConfig* config);
// Fills derived defaults (threads, helper path); returns an error message or
// "" when the configuration is usable.
std::string FinalizeConfig(ServerConfig* config);

}  // namespace dot::server

#endif  // DOT_SERVER_CONFIG_H_
