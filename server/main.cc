// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-server: the gRPC front door of the dot triangulation core.
#include <malloc.h>
#include <signal.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <memory>
#include <thread>

#include "config.h"
#include "dot/table_memory.h"
#include "dot_server.h"
#include "listener_watchdog.h"
#include "log_format.h"

// Exit status when the listener stopped accepting (EX_SOFTWARE).
constexpr int kExitListenerDead = 70;

int main(int argc, char** argv) {
  CLI::App app{
      "dot-server: optimal, intersection-free triangulation of 3D polygons "
      "over gRPC (dot.v1.Triangulator).\nEvery option can also be set by the "
      "environment variable shown."};
  dot::server::ServerConfig config;
  dot::server::AddServerFlags(app, &config);
  app.set_version_flag("--version", "dot-server " DOT_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a bad flag or environment variable 2.
    return app.exit(e) == 0 ? 0 : 2;
  }

  dot::server::SetLogFormat(config.log_format == "json");
  if (config.log_format != "text" && config.log_format != "json") {
    spdlog::error("unknown --log-format '{}' (text or json)",
                  config.log_format);
    return 2;
  }
  const auto level = spdlog::level::from_str(config.log_level);
  if (level == spdlog::level::off && config.log_level != "off") {
    spdlog::error("unknown --log-level '{}'", config.log_level);
    return 2;
  }
  spdlog::set_level(level);

  // By default glibc maps large blocks fresh for every request and hands
  // freed compute-thread heaps back to the kernel, so each solve page-faults
  // its tables in again: a quarter of a 2,000-vertex request's time here.
  // Keeping up to --malloc-keep-mb of freed memory makes repeated solves
  // reuse warm pages: half in malloc's free lists, half as the solve's
  // large tables, which the core maps apart from malloc.
  if (config.service.malloc_keep_bytes > 0) {
    const auto keep = static_cast<int>(
        std::min<int64_t>(config.service.malloc_keep_bytes, int64_t{1} << 30));
    mallopt(M_MMAP_THRESHOLD, keep / 2);
    mallopt(M_TRIM_THRESHOLD, keep / 2);
    dot::SetTableCacheBytes(static_cast<size_t>(keep / 2));
  }

  // Every connection costs a file descriptor: use all the hard limit
  // allows (gRPC stops accepting for good once it runs out; see
  // listener_watchdog.h).
  rlimit files{};
  if (getrlimit(RLIMIT_NOFILE, &files) == 0 &&
      files.rlim_cur < files.rlim_max) {
    files.rlim_cur = files.rlim_max;
    setrlimit(RLIMIT_NOFILE, &files);
  }

  // Signals are taken synchronously by this thread; every other thread
  // (gRPC's, the pool's) inherits the blocked mask. SIGUSR1 comes from the
  // listener watchdog.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGUSR1);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  std::string error;
  auto server = dot::server::DotServer::Start(config, &error);
  if (!server) {
    spdlog::error("{}", error);
    return 1;
  }
  std::unique_ptr<dot::server::ListenerWatchdog> watchdog;
  if (config.listener_patience_s > 0) {
    dot::server::ListenerWatchdogOptions options;
    options.patience = std::chrono::seconds(config.listener_patience_s);
    watchdog = std::make_unique<dot::server::ListenerWatchdog>(
        server->port(), options, [](const std::string& why) {
          spdlog::error("{}; exiting so that a supervisor restarts it", why);
          kill(getpid(), SIGUSR1);
        });
  }
  if (config.exit_with_stdin) {
    // Detached: it lives as long as the process, blocked on read(2).
    std::thread([] {
      char buf[256];
      while (::read(STDIN_FILENO, buf, sizeof buf) > 0) {
      }
      spdlog::info("stdin closed: the parent is gone");
      kill(getpid(), SIGTERM);
    }).detach();
  }
  int sig = 0;
  sigwait(&signals, &sig);
  const bool deaf = sig == SIGUSR1;
  if (!deaf) {
    spdlog::info("received {}, shutting down",
                 sig == SIGTERM ? "SIGTERM" : "SIGINT");
  }
  watchdog.reset();
  server->Drain(std::chrono::seconds(config.drain_seconds));
  return deaf ? kExitListenerDead : 0;
}
