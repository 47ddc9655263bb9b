// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl health | info | source: the standard health check, the server's
// description and limits, and its source code (AGPL-3.0 section 13).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "cli/json_envelope.h"
#include "commands.h"
#include "dot/v1/triangulation.pb.h"
#include "exit_codes.h"
#include "grpc/health/v1/health.pb.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

std::string MsText(std::chrono::steady_clock::time_point t0) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f ms", MsSince(t0));
  return buf;
}

// --json: the envelope of one call (no input; `s` null: no call made),
// its own fields after, on `os`.
void PrintCallJson(std::ostream& os, const grpc::Status* s,
                   const std::string& outcome, int exit_code,
                   const std::string& error, double latency_ms,
                   const std::string& output,
                   std::vector<std::pair<std::string, std::string>> fields) {
  JsonEnvelope e;
  e.outcome = outcome;
  e.exit_code = exit_code;
  if (s != nullptr) e.rpc_status = s->error_code();
  e.error = error;
  e.output = output;
  e.latency_ms = latency_ms;
  e.fields = std::move(fields);
  os << e.ToJson() << std::endl;
}

// The outcome of a call that failed (the README's outcomes).
std::string OutcomeOf(const grpc::Status& s) {
  return s.ok() ? "ok" : "call_failed";
}

}  // namespace

void AddHealthCommand(CLI::App& app, Context* ctx) {
  auto service = std::make_shared<std::string>();
  auto timeout = std::make_shared<double>(3);
  CLI::App* cmd = app.add_subcommand(
      "health",
      "Ask grpc.health.v1.Health/Check. Exit code 0 when SERVING, 1 when "
      "not (NOT_SERVING, SERVICE_UNKNOWN for a --service the server does "
      "not know), 3 when the server cannot be reached: fit for container "
      "health checks.");
  cmd->add_option("--service", *service,
                  "service to check ('' is the whole server, or "
                  "dot.v1.Triangulator)");
  cmd->add_option("--health-timeout", *timeout, "seconds to wait")
      ->capture_default_str();
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json,
                "one JSON object on stdout (the envelope, then \"status\")");
  cmd->callback([ctx, service, timeout, json] {
    const Connection server = ConnectOrReport(ctx, *json);
    if (!server) return;
    grpc::health::v1::HealthCheckResponse response;
    const auto t0 = std::chrono::steady_clock::now();
    const grpc::Status s = server.calls->check_health(server.channel, *service,
                                                      *timeout, &response);
    PrintVerbose(*ctx, "Check answered in " + MsText(t0));
    // Not reached, a service the server does not know (NOT_FOUND, as the
    // health protocol answers), or another failure (no health service).
    const bool unreachable =
        s.error_code() == grpc::StatusCode::UNAVAILABLE ||
        s.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED;
    const std::string status =
        s.ok() ? grpc::health::v1::HealthCheckResponse::ServingStatus_Name(
                     response.status())
        : unreachable                                   ? "UNREACHABLE"
        : s.error_code() == grpc::StatusCode::NOT_FOUND ? "SERVICE_UNKNOWN"
                                                        : "ERROR";
    const int code =
        !s.ok() ? (unreachable ? kExitUnavailable : kExitFailed)
        : response.status() == grpc::health::v1::HealthCheckResponse::SERVING
            ? kExitOk
            : kExitFailed;
    RaiseExitCode(ctx, code);
    if (*json) {
      PrintCallJson(std::cout, &s,
                    s.ok() && code != kExitOk ? "not_serving" : OutcomeOf(s),
                    code, s.error_message(), MsSince(t0), "",
                    {{"status", JsonQuote(status)}});
      return;
    }
    if (!s.ok()) {
      PrintError(status + " (" +
                 std::string(wire::GrpcCodeName(s.error_code())) + ": " +
                 s.error_message() + ")");
      return;
    }
    if (!ctx->quiet) std::cout << status << "\n";
  });
}

void AddInfoCommands(CLI::App& app, Context* ctx) {
  CLI::App* info = app.add_subcommand(
      "info", "Show the server's version, backends, limits and license.");
  auto info_json = std::make_shared<bool>(false);
  info->add_flag("--json", *info_json,
                 "one JSON object on stdout (the envelope, then "
                 "\"server_info\": the ServerInfo message)");
  info->callback([ctx, info_json] {
    const Connection server = ConnectOrReport(ctx, *info_json);
    if (!server) return;
    v1::ServerInfo i;
    const auto t0 = std::chrono::steady_clock::now();
    const grpc::Status s = server.calls->server_info(
        server.channel, ctx->connection.timeout_s, &i);
    PrintVerbose(*ctx, "GetServerInfo answered in " + MsText(t0));
    RaiseExitCode(ctx, ExitCodeFor(s));
    if (*info_json) {
      PrintCallJson(std::cout, &s, OutcomeOf(s), ExitCodeFor(s),
                    s.error_message(), MsSince(t0), "",
                    {{"server_info", s.ok() ? ProtoJson(i) : "null"}});
      return;
    }
    if (!s.ok()) {
      PrintError(std::string(wire::GrpcCodeName(s.error_code())) + ": " +
                 s.error_message());
      return;
    }
    if (ctx->quiet) return;
    std::cout << "version   " << i.version() << "\nbuild     " << i.build()
              << "\nbackends ";
    for (const auto& b : i.backends()) std::cout << " [" << b << "]";
    const auto& l = i.limits();
    std::cout << "\nlimits    max_vertices=" << l.max_vertices()
              << " max_compute_ms=" << l.max_compute_ms()
              << " memory_budget_mb=" << (l.memory_budget_bytes() >> 20)
              << " threads=" << l.compute_threads()
              << " queue=" << l.queue_size()
              << " all_space_max_vertices=" << l.all_space_max_vertices()
              << " max_message_mb=" << (l.max_message_bytes() >> 20)
              << "\nlicense   " << i.license() << "\nsource    "
              << (i.source_url().empty() ? "(no URL set)" : i.source_url())
              << "\n          " << i.source_note() << "\n";
  });

  auto out = std::make_shared<std::string>("dot-source.tar.gz");
  CLI::App* source = app.add_subcommand(
      "source", "Download the server's complete source code (tar.gz).");
  source
      ->add_option("-o,--output", *out,
                   "file to write (- for stdout); written to a temporary "
                   "file renamed into place once complete, so a failed call "
                   "leaves nothing behind")
      ->capture_default_str();
  auto source_json = std::make_shared<bool>(false);
  source->add_flag("--json", *source_json,
                   "one JSON object on stdout, or stderr with -o - (the "
                   "envelope, then \"bytes\")");
  source->callback([ctx, out, source_json] {
    // Checked before the call: the file can be written.
    AtomicOutput file;
    const std::string unusable = file.Open(*out);
    std::ostream& json_out = *out == "-" ? std::cerr : std::cout;
    if (!unusable.empty()) {
      RaiseExitCode(ctx, kExitUsage);
      if (*source_json) {
        PrintCallJson(json_out, nullptr, "output_error", kExitUsage, unusable,
                      0, "", {{"bytes", "0"}});
      } else {
        PrintError(unusable);
      }
      return;
    }
    const Connection server = ConnectOrReport(ctx, *source_json);
    if (!server) return;
    const auto t0 = std::chrono::steady_clock::now();
    size_t bytes = 0;
    const grpc::Status s = server.calls->source(
        server.channel, ctx->connection.timeout_s,
        [&](const std::string& data) {
          file.stream().write(data.data(),
                              static_cast<std::streamsize>(data.size()));
          bytes += data.size();
        });
    PrintVerbose(*ctx, "GetSource: " + std::to_string(bytes) + " bytes in " +
                           MsText(t0));
    const std::string written = s.ok() ? file.Commit() : "";
    const int code = !s.ok()           ? ExitCodeFor(s)
                     : written.empty() ? kExitOk
                                       : kExitFailed;
    RaiseExitCode(ctx, code);
    if (*source_json) {
      PrintCallJson(json_out, &s,
                    !s.ok()           ? "call_failed"
                    : written.empty() ? "ok"
                                      : "write_failed",
                    code, s.ok() ? written : s.error_message(), MsSince(t0),
                    code == kExitOk ? *out : "",
                    {{"bytes", std::to_string(code == kExitOk ? bytes : 0)}});
      return;  // a failed call's temporary file goes with `file`
    }
    if (!s.ok()) {
      PrintError(std::string(wire::GrpcCodeName(s.error_code())) + ": " +
                 s.error_message());
      return;  // the temporary file goes with `file`
    }
    if (!written.empty()) {
      PrintError(written);
      return;
    }
    if (!ctx->quiet) {
      (*out == "-" ? std::cerr : std::cout)
          << "wrote " << bytes << " bytes to " << *out << std::endl;
    }
  });
}

}  // namespace dot::client
