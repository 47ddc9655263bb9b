// SPDX-License-Identifier: AGPL-3.0-or-later
#include "cli/context.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "cli/json_envelope.h"
#include "exit_codes.h"
#include "remote_call.h"

namespace dot::client {

void RaiseExitCode(Context* ctx, int code) {
  if (code == kExitOk) return;
  if (code == kExitNoTriangulation) {
    if (ctx->exit_code == kExitOk) ctx->exit_code = code;
    return;
  }
  const int now = ctx->exit_code == kExitNoTriangulation ? 0 : ctx->exit_code;
  ctx->exit_code = std::max(now, code);
}

void PrintError(const std::string& message) {
  std::cout.flush();
  std::cerr << "dotctl: " << message << std::endl;
}

void PrintVerbose(const Context& ctx, const std::string& message) {
  if (ctx.verbose) std::cerr << "dotctl: " << message << std::endl;
}

Connection ConnectOrReport(Context* ctx, bool json) {
  std::string error;
  Connection c;
  c.calls = LoadRemoteCalls(&error);
  if (c.calls != nullptr)
    c.channel = c.calls->make_channel(ctx->connection, &error);
  if (!c.channel) {
    if (json) {
      JsonEnvelope e;
      e.outcome = "connection_error";
      e.exit_code = kExitUsage;
      e.error = error;
      std::cout << e.ToJson() << std::endl;
    } else {
      PrintError(error);
    }
    RaiseExitCode(ctx, kExitUsage);
    return {};
  }
  char timeout[32];
  std::snprintf(timeout, sizeof timeout, "%g", ctx->connection.timeout_s);
  PrintVerbose(
      *ctx, "server " + ctx->connection.server +
                (ctx->connection.tls_ca.empty() ? " (plaintext)" : " (TLS)") +
                ", deadline " + timeout + " s a call");
  return c;
}

int ExitCodeFor(const grpc::Status& status) {
  switch (status.error_code()) {
    case grpc::StatusCode::OK:
      return kExitOk;
    case grpc::StatusCode::UNAVAILABLE:
      return kExitUnavailable;
    default:
      return kExitFailed;
  }
}

}  // namespace dot::client
