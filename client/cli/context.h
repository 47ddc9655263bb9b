// SPDX-License-Identifier: AGPL-3.0-or-later
// What every dotctl subcommand shares: the context its flags fill, exit
// codes (the most serious outcome wins), error and verbose lines on
// stderr, and the channel to the server.
#ifndef DOT_CLIENT_CLI_CONTEXT_H_
#define DOT_CLIENT_CLI_CONTEXT_H_

#include <grpcpp/support/status.h>

#include <memory>
#include <string>

#include "remote_calls.h"
#include "request_flags.h"

namespace dot::client {

struct Context {
  ConnectionFlags connection;
  int exit_code = 0;
  bool quiet = false;    // -q: errors only (and what --json asks for)
  bool verbose = false;  // -v: timing lines on stderr
};

// Raises ctx->exit_code to `code`: the most serious outcome wins (2 and 3
// over 1), and 4 (no triangulation) only over 0.
void RaiseExitCode(Context* ctx, int code);
// "dotctl: <message>" on stderr, always (also with -q).
void PrintError(const std::string& message);
// "dotctl: <message>" on stderr with -v.
void PrintVerbose(const Context& ctx, const std::string& message);

// The exit code of an RPC's status (exit_codes.h).
int ExitCodeFor(const grpc::Status& status);
// A connection to ctx->connection: the remote calls (loaded on first use)
// and a channel. Null after reporting a usage error (exit 2): on stderr, or
// with `json` as the subcommand's envelope with outcome "connection_error"
// on stdout (an unreadable TLS file, the remote module missing, say).
struct Connection {
  const RemoteCalls* calls = nullptr;
  Channel channel;
  explicit operator bool() const { return channel != nullptr; }
};
Connection ConnectOrReport(Context* ctx, bool json);

}  // namespace dot::client

#endif  // DOT_CLIENT_CLI_CONTEXT_H_
