// SPDX-License-Identifier: AGPL-3.0-or-later
#include "config.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <thread>

namespace dot::server {

void AddServerFlags(CLI::App& app, ServerConfig* c) {
  auto add = [&app](const std::string& name, auto* value,
                    const std::string& env, const std::string& help) {
    app.add_option(name, *value, help)->envname(env)->capture_default_str();
  };
  add("--listen", &c->listen, "DOT_LISTEN", "gRPC address to listen on");
  add("--threads", &c->threads, "DOT_THREADS",
      "compute threads (0: number of cores)");
  add("--queue-size", &c->queue_size, "DOT_QUEUE_SIZE",
      "requests that may wait for a compute thread; beyond it the server "
      "answers RESOURCE_EXHAUSTED");
  add("--max-vertices", &c->max_vertices, "DOT_MAX_VERTICES",
      "largest polygon accepted");
  add("--max-compute-ms", &c->max_compute_ms, "DOT_MAX_COMPUTE_MS",
      "compute time limit per request");
  add("--memory-budget-mb", &c->memory_budget_mb, "DOT_MEMORY_BUDGET_MB",
      "table memory limit per request");
  add("--all-space-max-vertices", &c->all_space_max_vertices,
      "DOT_ALL_SPACE_MAX_VERTICES",
      "search space 'auto' falls back to all triangles up to this size");
  app.add_option("--delaunay-backend", c->delaunay_backend,
                 "3D Delaunay backend of requests that do not choose one")
      ->envname("DOT_DELAUNAY_BACKEND")
      ->check(CLI::IsMember({"cgal", "tetgen"}))
      ->capture_default_str();
  add("--cache-mb", &c->cache_mb, "DOT_CACHE_MB",
      "memory for recently used search spaces, so re-solving a polygon with "
      "new weights runs only the dynamic program (0: no cache)");
  add("--malloc-keep-mb", &c->malloc_keep_mb, "DOT_MALLOC_KEEP_MB",
      "freed memory the allocator keeps for the next requests instead of "
      "returning it to the kernel (at most 1024; 0: glibc's defaults)");
  add("--inline-max-vertices", &c->inline_max_vertices,
      "DOT_INLINE_MAX_VERTICES",
      "Triangulate calls up to this many vertices run on the RPC thread when "
      "a compute slot is free, saving two thread handoffs (0: never)");
  add("--delaunay-helpers", &c->delaunay_helpers, "DOT_DELAUNAY_HELPERS",
      "TetGen helper processes (-1: one per thread, 0: in-process, "
      "serialized)");
  add("--helper-path", &c->helper_path, "DOT_HELPER_PATH",
      "dot-delaunay-helper binary (default: next to dot-server)");
  add("--helper-memory-mb", &c->helper_memory_mb, "DOT_HELPER_MEMORY_MB",
      "address-space limit of each helper process");
  add("--metrics-port", &c->metrics_port, "DOT_METRICS_PORT",
      "Prometheus /metrics HTTP port (0: off)");
  add("--metrics-bind", &c->metrics_bind, "DOT_METRICS_BIND",
      "address the metrics endpoint binds");
  add("--tls-cert", &c->tls_cert, "DOT_TLS_CERT",
      "PEM server certificate (enables TLS)");
  add("--tls-key", &c->tls_key, "DOT_TLS_KEY", "PEM server private key");
  add("--tls-client-ca", &c->tls_client_ca, "DOT_TLS_CLIENT_CA",
      "PEM CA bundle; when set, clients must present a certificate it "
      "signed (mutual TLS)");
  add("--drain-seconds", &c->drain_seconds, "DOT_DRAIN_SECONDS",
      "on SIGTERM, time in-flight requests get to finish before they are "
      "cancelled");
  add("--max-message-mb", &c->max_message_mb, "DOT_MAX_MESSAGE_MB",
      "largest gRPC message accepted or sent");
  add("--chunk-kb", &c->chunk_kb, "DOT_CHUNK_KB",
      "approximate size of streamed mesh chunks");
  add("--max-connection-age-s", &c->max_connection_age_s,
      "DOT_MAX_CONNECTION_AGE_S",
      "close client connections after this long so load rebalances across "
      "replicas (0: never)");
  add("--log-level", &c->log_level, "DOT_LOG_LEVEL",
      "trace, debug, info, warn, error or off");
  add("--source-archive", &c->source_archive, "DOT_SOURCE_ARCHIVE",
      "tar.gz of this server's source, served by GetSource (AGPL-3.0 s. 13)");
  add("--source-url", &c->source_url, "DOT_SOURCE_URL",
      "where this server's source is published, reported by GetServerInfo");
}

std::string FinalizeConfig(ServerConfig* c) {
  if (c->threads <= 0) {
    c->threads =
        static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
  if (c->delaunay_helpers < 0) c->delaunay_helpers = c->threads;
  if (c->helper_path.empty() && c->delaunay_helpers > 0) {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    c->helper_path = (self.parent_path() / "dot-delaunay-helper").string();
  }
  if (c->delaunay_helpers > 0 && ::access(c->helper_path.c_str(), X_OK) != 0) {
    return "Delaunay helper '" + c->helper_path +
           "' is not executable; set --helper-path or --delaunay-helpers 0";
  }
  if (c->queue_size < 0) return "--queue-size must be >= 0";
  if (c->max_vertices < 3) return "--max-vertices must be >= 3";
  if (c->max_compute_ms <= 0) return "--max-compute-ms must be > 0";
  if (c->tls_cert.empty() != c->tls_key.empty()) {
    return "--tls-cert and --tls-key go together";
  }
  if (!c->tls_client_ca.empty() && c->tls_cert.empty()) {
    return "--tls-client-ca needs --tls-cert and --tls-key";
  }
  return "";
}

}  // namespace dot::server
