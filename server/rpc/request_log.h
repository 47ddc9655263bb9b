// SPDX-License-Identifier: AGPL-3.0-or-later
// The record of one answered polygon: the request counter and latency
// histogram, and one log line (id, n, metric mix, space, status, queue and
// compute time). Client-chosen text (the id) is escaped, so it cannot forge
// log lines.
#ifndef DOT_SERVER_RPC_REQUEST_LOG_H_
#define DOT_SERVER_RPC_REQUEST_LOG_H_

#include <grpcpp/grpcpp.h>

#include <string>
#include <string_view>

#include "server_metrics.h"

namespace dot::server {

struct Job;

void LogRequest(const Job& job, const grpc::Status& status,
                ServerMetrics* metrics);

// `text` with control characters, quotes, backslashes and non-ASCII bytes
// written as \xHH (printable ASCII is kept), cut to `max_bytes` input bytes.
std::string EscapeForLog(std::string_view text, size_t max_bytes = 256);

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_REQUEST_LOG_H_
