// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-server: the gRPC front door of the dot triangulation core.
#include <malloc.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>

#include "config.h"
#include "dot_server.h"

int main(int argc, char** argv) {
  CLI::App app{
      "dot-server: optimal, intersection-free triangulation of 3D polygons "
      "over gRPC (dot.v1.Triangulator).\nEvery option can also be set by the "
      "environment variable shown."};
  dot::server::ServerConfig config;
  dot::server::AddServerFlags(app, &config);
  app.set_version_flag("--version", "dot-server " DOT_VERSION);
  CLI11_PARSE(app, argc, argv);

  const auto level = spdlog::level::from_str(config.log_level);
  if (level == spdlog::level::off && config.log_level != "off") {
    spdlog::error("unknown --log-level '{}'", config.log_level);
    return 2;
  }
  spdlog::set_level(level);
  spdlog::set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");

  // By default glibc maps large blocks fresh for every request and hands
  // freed compute-thread heaps back to the kernel, so each solve page-faults
  // its tables in again: a quarter of a 2,000-vertex request's time here.
  // Keeping up to --malloc-keep-mb of freed memory makes repeated solves
  // reuse warm pages.
  if (config.service.malloc_keep_bytes > 0) {
    const auto keep = static_cast<int>(
        std::min<int64_t>(config.service.malloc_keep_bytes, int64_t{1} << 30));
    mallopt(M_MMAP_THRESHOLD, keep / 2);
    mallopt(M_TRIM_THRESHOLD, keep);
  }

  // Signals are taken synchronously by this thread; every other thread
  // (gRPC's, the pool's) inherits the blocked mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  std::string error;
  auto server = dot::server::DotServer::Start(config, &error);
  if (!server) {
    spdlog::error("{}", error);
    return 1;
  }
  int sig = 0;
  sigwait(&signals, &sig);
  spdlog::info("received {}, shutting down",
               sig == SIGTERM ? "SIGTERM" : "SIGINT");
  server->Drain(std::chrono::seconds(config.drain_seconds));
  return 0;
}
