// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/request_log.h"

#include <spdlog/spdlog.h>

#include <sstream>

#include "rpc/job.h"
#include "wire/wire.h"

namespace dot::server {
namespace {

std::string WeightsLabel(const MetricWeights& w) {
  std::ostringstream s;
  for (Metric m : kAllMetrics) {
    if (w[m] == 0) continue;
    if (s.tellp() > 0) s << ',';
    s << MetricName(m) << '=' << w[m];
  }
  return s.tellp() > 0 ? s.str() : "area=1";
}

}  // namespace

std::string EscapeForLog(std::string_view text, size_t max_bytes) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
      out += static_cast<char>(c);
    } else {
      out += {'\\', 'x', kHex[c >> 4], kHex[c & 15]};
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out;
}

void LogRequest(const Job& job, const grpc::Status& status,
                ServerMetrics* metrics) {
  std::string label(wire::GrpcCodeName(status.error_code()));
  if (status.ok() && job.ran &&
      job.result.status.code == StatusCode::kNoTriangulation) {
    label = "NO_TRIANGULATION";
  }
  metrics->RequestDone(job.rpc, label, Ms(Clock::now() - job.arrived) / 1000);
  const StopReason stop = job.stop;
  if (stop != StopReason::kNone) {
    metrics->RequestStopped(job.rpc, std::string(StopReasonName(stop)));
  }
  // Only a call that did not end OK was stopped, whatever came late.
  const std::string stopped =
      stop == StopReason::kNone || status.ok()
          ? std::string()
          : " stop=" + std::string(StopReasonName(stop));
  const bool ran = job.ran;
  if (!job.log_detail.empty()) {
    spdlog::info(
        "rpc={} id=\"{}\" {} status={}{} queue_ms={:.1f} compute_ms={:.1f}{}{}",
        job.rpc, EscapeForLog(job.id), job.log_detail, label, stopped,
        ran ? Ms(job.started - job.arrived) : 0.0,
        ran ? Ms(job.finished - job.started) : 0.0,
        status.ok() ? "" : " message=\"",
        status.ok() ? "" : EscapeForLog(status.error_message(), 1024) + "\"");
    return;
  }
  spdlog::info(
      "rpc={} id=\"{}\" n={} weights={} space={} status={}{} "
      "queue_ms={:.1f} compute_ms={:.1f} triangles={}{}{}",
      job.rpc, EscapeForLog(job.id), job.problem.vertices.size(),
      WeightsLabel(job.problem.weights),
      ran ? SpaceUsedName(job.result.space_used)
          : SearchSpaceName(job.options.space),
      label, stopped, ran ? Ms(job.started - job.arrived) : 0.0,
      ran ? Ms(job.finished - job.started) : 0.0,
      ran && status.ok() ? job.result.triangles.size() : 0,
      status.ok() ? "" : " message=\"",
      status.ok() ? "" : EscapeForLog(status.error_message(), 1024) + "\"");
}

}  // namespace dot::server
