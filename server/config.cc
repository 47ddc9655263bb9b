// SPDX-License-Identifier: AGPL-3.0-or-later
#include "config.h"

#include <arpa/inet.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <thread>

namespace dot::server {
namespace {

// Where a flag's value came from, for its error: the environment (when
// the variable holds that value; the command line wins, so a value from
// both is the same) or the command line.
std::string Origin(const std::string& env, const std::string& value) {
  const char* from_env = std::getenv(env.c_str());
  if (from_env && value == from_env) {
    return "the environment variable " + env + "='" + value + "'";
  }
  return "'" + value + "'";
}

// Checks an integer flag's text before CLI11 converts it: a whole number
// within [min, max], or an error that names the flag, the environment
// variable (when the value came from there) and what is wrong.
CLI::Validator IntegerIn(const std::string& env, int64_t min, int64_t max) {
  return CLI::Validator(
      [env, min, max](std::string& value) -> std::string {
        errno = 0;
        char* end = nullptr;
        const long long v = std::strtoll(value.c_str(), &end, 10);
        const bool whole = !value.empty() && end && *end == '\0' &&
                           !std::isspace(static_cast<unsigned char>(value[0]));
        if (!whole) return Origin(env, value) + " is not an integer";
        if (errno != ERANGE && v >= min && v <= max) return std::string();
        return Origin(env, value) + " is out of range: it must be " +
               (v < min ? "at least " + std::to_string(min)
                        : "at most " + std::to_string(max));
      },
      "", "integer");
}

// The largest value of T that an int64_t holds.
template <typename T>
int64_t TypeMax() {
  const uint64_t type_max = std::min<uint64_t>(
      static_cast<uint64_t>(std::numeric_limits<T>::max()),
      static_cast<uint64_t>(std::numeric_limits<int64_t>::max()));
  return static_cast<int64_t>(type_max);
}

template <typename T>
void Add(CLI::App& app, const std::string& name, T* value,
         const std::string& env, const std::string& help) {
  app.add_option(name, *value, help)->envname(env)->capture_default_str();
}

// A file flag that, once given, must name a file: an empty --tls-cert
// (e.g. from an unset variable in a script) would otherwise mean "no TLS"
// and start a plaintext server. (CLI11 skips an empty environment
// variable: unset and empty mean the same there.)
void AddPath(CLI::App& app, const std::string& name, std::string* value,
             const std::string& env, const std::string& help) {
  app.add_option(name, *value, help)
      ->envname(env)
      ->check(CLI::Validator(
          [](std::string& path) -> std::string {
            return path.empty() ? "is empty: name a file, or leave the flag out"
                                : "";
          },
          "", "path"));
}

// An integer flag: refused, naming its environment variable, unless it is
// a whole number from `min` (0 by default: counts are never negative).
template <typename T>
void AddInt(CLI::App& app, const std::string& name, T* value,
            const std::string& env, const std::string& help, int64_t min = 0,
            int64_t max = std::numeric_limits<int64_t>::max()) {
  app.add_option(name, *value, help)
      ->envname(env)
      ->capture_default_str()
      ->check(IntegerIn(env, min, std::min(max, TypeMax<T>())));
}

// A size flag in units of 2^shift bytes (MiB: 20, KiB: 10) bound to a field
// in bytes.
template <typename T>
void AddSize(CLI::App& app, const std::string& name, int shift, T* bytes,
             const std::string& env, const std::string& help) {
  // Unsigned fields (size_t) reach past int64_t: clamp before shifting.
  const int64_t max = TypeMax<T>() >> shift;
  app.add_option_function<int64_t>(
         name,
         [bytes, shift](int64_t v) { *bytes = static_cast<T>(v << shift); },
         help)
      ->envname(env)
      ->check(IntegerIn(env, 0, max))
      ->default_str(std::to_string(static_cast<int64_t>(*bytes) >> shift));
}

}  // namespace

void AddServerFlags(CLI::App& app, ServerConfig* c) {
  ServiceOptions& s = c->service;
  Add(app, "--listen", &c->listen, "DOT_LISTEN", "gRPC address to listen on");
  AddInt(app, "--threads", &c->pool.threads, "DOT_THREADS",
         "compute threads (0: number of cores)");
  AddInt(app, "--queue-size", &c->pool.queue_size, "DOT_QUEUE_SIZE",
         "requests that may wait for a compute thread; beyond it the server "
         "answers RESOURCE_EXHAUSTED");
  AddInt(app, "--max-vertices", &s.max_vertices, "DOT_MAX_VERTICES",
         "largest polygon accepted", 3);
  AddInt(app, "--max-compute-ms", &s.max_compute_ms, "DOT_MAX_COMPUTE_MS",
         "compute time limit per request", 1);
  AddSize(app, "--memory-budget-mb", 20, &s.solve.memory_budget_bytes,
          "DOT_MEMORY_BUDGET_MB",
          "table memory limit per request (requests may ask for less)");
  AddInt(app, "--all-space-max-vertices", &s.solve.all_space_max_vertices,
         "DOT_ALL_SPACE_MAX_VERTICES",
         "search space 'auto' falls back to all triangles up to this size");
  app.add_option_function<std::string>(
         "--delaunay-backend",
         [&s](const std::string& name) {
           s.solve.delaunay =
               DelaunayBackendFromName(name).value_or(s.solve.delaunay);
         },
         "3D Delaunay backend of requests that do not choose one")
      ->envname("DOT_DELAUNAY_BACKEND")
      ->check(CLI::IsMember({"cgal", "tetgen"}))
      ->default_str(std::string(DelaunayBackendName(s.solve.delaunay)));
  AddInt(app, "--parallel-delaunay-min-points",
         &s.solve.parallel_delaunay_min_points,
         "DOT_PARALLEL_DELAUNAY_MIN_POINTS",
         "polygons with at least this many vertices get CGAL's parallel "
         "(TBB) Delaunay step (default: never; measured slower on 2 cores)");
  AddInt(app, "--delaunay-threads", &s.solve.delaunay_threads,
         "DOT_DELAUNAY_THREADS",
         "threads of the parallel Delaunay step (0: all cores); results do not "
         "depend on it");
  AddSize(app, "--cache-mb", 20, &c->cache_bytes, "DOT_CACHE_MB",
          "memory for recently used search spaces, so re-solving a polygon "
          "with new weights runs only the dynamic program (0: no cache)");
  AddSize(app, "--malloc-keep-mb", 20, &s.malloc_keep_bytes,
          "DOT_MALLOC_KEEP_MB",
          "freed memory kept for the next requests instead of returned "
          "to the kernel, half in malloc, half as solve tables (at most "
          "1024; 0: glibc's defaults, no tables kept)");
  AddInt(app, "--inline-max-vertices", &s.inline_max_vertices,
         "DOT_INLINE_MAX_VERTICES",
         "Triangulate calls over the Delaunay space up to this many vertices "
         "run on the RPC thread when a compute slot is free, saving a thread "
         "handoff (0: never)");
  AddInt(app, "--fill-max-faces", &s.fill_max_faces, "DOT_FILL_MAX_FACES",
         "largest mesh FillHoles accepts, in faces (a call holds up to 100 "
         "bytes a vertex and 300 a face: 3.5 GB at the defaults)");
  AddSize(app, "--fill-memory-mb", 20, &s.fill_memory_bytes,
          "DOT_FILL_MEMORY_MB",
          "memory all FillHoles calls may hold at once, uploads included; a "
          "call that would exceed it is answered RESOURCE_EXHAUSTED");
  AddInt(app, "--fill-max-vertices", &s.fill_max_vertices,
         "DOT_FILL_MAX_VERTICES",
         "largest mesh FillHoles accepts, in vertices");
  AddInt(app, "--delaunay-helpers", &c->helpers.count, "DOT_DELAUNAY_HELPERS",
         "helper processes for TetGen and large fairing solves (-1: one per "
         "thread; 0: none, TetGen refused, fairing in-process)",
         -1);
  Add(app, "--helper-path", &c->helpers.executable, "DOT_HELPER_PATH",
      "dot-delaunay-helper binary (default: next to dot-server)");
  AddSize(app, "--helper-memory-mb", 20, &c->helpers.memory_limit_bytes,
          "DOT_HELPER_MEMORY_MB",
          "address-space limit of each helper process (0: no limit)");
  AddInt(app, "--metrics-port", &c->metrics.port, "DOT_METRICS_PORT",
         "Prometheus /metrics HTTP port (0: off)", 0, 65535);
  Add(app, "--metrics-bind", &c->metrics.bind, "DOT_METRICS_BIND",
      "IPv4 or IPv6 address the metrics endpoint binds");
  AddPath(app, "--tls-cert", &c->tls.cert, "DOT_TLS_CERT",
          "PEM server certificate (enables TLS)");
  AddPath(app, "--tls-key", &c->tls.key, "DOT_TLS_KEY",
          "PEM server private key");
  AddPath(app, "--tls-client-ca", &c->tls.client_ca, "DOT_TLS_CLIENT_CA",
          "PEM CA bundle; when set, clients must present a certificate it "
          "signed (mutual TLS)");
  app.add_flag("--exit-with-stdin", c->exit_with_stdin,
               "drain and exit when stdin reaches end of file (for a parent "
               "that holds a pipe to it: the server ends with the parent)");
  Add(app, "--health-listen", &c->health_listen, "DOT_HEALTH_LISTEN",
      "plaintext address serving only gRPC health (e.g. 127.0.0.1:50052), "
      "for health checks of a TLS server; default: none");
  AddInt(app, "--drain-seconds", &c->drain_seconds, "DOT_DRAIN_SECONDS",
         "on SIGTERM, time in-flight requests get to finish before they are "
         "cancelled");
  AddSize(app, "--max-message-mb", 20, &s.max_message_bytes,
          "DOT_MAX_MESSAGE_MB", "largest gRPC message accepted or sent");
  AddSize(app, "--chunk-kb", 10, &s.chunk_bytes, "DOT_CHUNK_KB",
          "approximate size of streamed mesh chunks");
  AddInt(app, "--max-connection-age-s", &c->max_connection_age_s,
         "DOT_MAX_CONNECTION_AGE_S",
         "close client connections after this long so load rebalances across "
         "replicas (0: never)");
  AddInt(
      app, "--listener-patience-s", &c->listener_patience_s,
      "DOT_LISTENER_PATIENCE_S",
      "exit 70 (for a supervisor to restart) when connections wait this long "
      "unaccepted, as after running out of file descriptors (0: never)");
  Add(app, "--log-level", &c->log_level, "DOT_LOG_LEVEL",
      "trace, debug, info, warn, error or off");
  Add(app, "--log-format", &c->log_format, "DOT_LOG_FORMAT",
      "text, or json: one object a line (time, level, message), for log "
      "collectors; times in UTC either way");
  Add(app, "--source-archive", &s.source_archive, "DOT_SOURCE_ARCHIVE",
      "tar.gz of this server's source, served by GetSource (AGPL-3.0 s. 13)");
  Add(app, "--source-url", &s.source_url, "DOT_SOURCE_URL",
      "where this server's source is published, reported by GetServerInfo");
}

std::string FinalizeConfig(ServerConfig* c) {
  if (c->pool.threads <= 0) {
    c->pool.threads =
        static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
  DelaunayHelperOptions& h = c->helpers;
  if (!TetgenAvailable()) {
    h.count = 0;
    if (c->service.solve.delaunay == DelaunayBackend::kTetgen) {
      return "--delaunay-backend tetgen: this build has no TetGen "
             "(DOT_WITH_TETGEN=OFF)";
    }
  }
  if (c->metrics.port > 0) {
    in6_addr address{};
    const bool ipv4 =
        ::inet_pton(AF_INET, c->metrics.bind.c_str(), &address) == 1;
    const bool ipv6 =
        ::inet_pton(AF_INET6, c->metrics.bind.c_str(), &address) == 1;
    if (!ipv4 && !ipv6) {
      // Before: civetweb took 999.1.1.1 and listened on 231.1.1.1.
      return "--metrics-bind '" + c->metrics.bind +
             "' is not an IPv4 or IPv6 address (e.g. 127.0.0.1 or 0.0.0.0)";
    }
    if (ipv6 && !MetricsSupportIpv6()) {
      return "--metrics-bind " + c->metrics.bind +
             ": this build's HTTP server (civetweb) has no IPv6; use an IPv4 "
             "address such as 127.0.0.1 or 0.0.0.0";
    }
  }
  if (h.count < 0) h.count = c->pool.threads;
  if (h.count == 0 && c->service.solve.delaunay == DelaunayBackend::kTetgen) {
    return "--delaunay-backend tetgen needs helper processes: TetGen aborts "
           "on some inputs and runs only in them (--delaunay-helpers is 0)";
  }
  if (h.executable.empty() && h.count > 0) {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    h.executable = (self.parent_path() / "dot-delaunay-helper").string();
  }
  if (h.count > 0 && ::access(h.executable.c_str(), X_OK) != 0) {
    return "Delaunay helper '" + h.executable +
           "' is not executable; set --helper-path or --delaunay-helpers 0";
  }
  ServiceOptions& s = c->service;
  if (c->pool.queue_size < 0) return "--queue-size must be >= 0";
  if (s.max_vertices < 3) return "--max-vertices must be >= 3";
  if (s.max_compute_ms <= 0) return "--max-compute-ms must be > 0";
  if (s.chunk_bytes == 0) return "--chunk-kb must be > 0";
  if (s.max_message_bytes <= 0) return "--max-message-mb must be > 0";
  // A polygon is 24 bytes a vertex on the wire (packed doubles): promise
  // only what a request message can carry.
  const int fits = (c->service.max_message_bytes - 4096) / 24;
  if (c->service.max_vertices > fits) {
    c->notes.push_back("--max-vertices " +
                       std::to_string(c->service.max_vertices) +
                       " lowered to " + std::to_string(fits) +
                       ": a larger polygon does not fit --max-message-mb " +
                       std::to_string(c->service.max_message_bytes >> 20));
    c->service.max_vertices = fits;
  }
  if (c->tls.cert.empty() != c->tls.key.empty()) {
    return "--tls-cert and --tls-key go together";
  }
  if (!c->tls.client_ca.empty() && c->tls.cert.empty()) {
    return "--tls-client-ca needs --tls-cert and --tls-key";
  }
  return "";
}

}  // namespace dot::server
