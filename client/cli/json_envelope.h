// SPDX-License-Identifier: AGPL-3.0-or-later
// The one JSON object dotctl prints per input with --json (version 1):
// the fields every subcommand shares, in this order, then its own
// (README.md, "Using the client").
#ifndef DOT_CLIENT_CLI_JSON_ENVELOPE_H_
#define DOT_CLIENT_CLI_JSON_ENVELOPE_H_

#include <google/protobuf/message.h>
#include <grpcpp/support/status.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dot::client {

struct JsonEnvelope {
  std::string input;    // as given ("-": stdin)
  std::string outcome;  // exit_codes.h: "ok", "call_failed", ...
  int exit_code = 0;
  std::optional<grpc::StatusCode> rpc_status;  // null: no call was made
  std::string error;                           // "" unless it failed
  std::string output;                          // "-" for stdout, "" none
  double latency_ms = 0;
  std::vector<std::string> notes;  // what was changed or noticed on the way
  // The subcommand's own fields, after the shared ones: name, JSON text.
  std::vector<std::pair<std::string, std::string>> fields;

  std::string ToJson() const;
};

// A JSON string literal.
std::string JsonQuote(const std::string& s);
// A message in the proto3 JSON mapping (field names as in the .proto,
// every field printed).
std::string ProtoJson(const google::protobuf::Message& message);

}  // namespace dot::client

#endif  // DOT_CLIENT_CLI_JSON_ENVELOPE_H_
