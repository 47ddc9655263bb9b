// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/job_response.h"

namespace dot::server {

grpc::Status StoppedStatus(StopReason why) {
  switch (why) {
    case StopReason::kDrain:
      return {grpc::StatusCode::UNAVAILABLE,
              "server is shutting down; retry on another replica"};
    case StopReason::kClientDeadline:
      return {grpc::StatusCode::DEADLINE_EXCEEDED,
              "the client's deadline passed"};
    case StopReason::kServerBudget:
      return {grpc::StatusCode::DEADLINE_EXCEEDED,
              "the request's time limit passed"};
    case StopReason::kClientGone:
      return {grpc::StatusCode::CANCELLED,
              "the client went away (a write to it failed)"};
    case StopReason::kClientCancel:
    case StopReason::kNone:
      break;
  }
  return {grpc::StatusCode::CANCELLED, "cancelled by the client"};
}

grpc::Status JobStatus(const Job& job, int max_compute_ms) {
  const Status& s = job.result.status;
  if (s.code == StatusCode::kCancelled) return StoppedStatus(job.stop);
  if (s.code == StatusCode::kDeadlineExceeded) {
    if (!job.deadline_is_limit) {
      return {grpc::StatusCode::DEADLINE_EXCEEDED,
              "the client's deadline passed (" + s.message + ")"};
    }
    // Name the limit that stopped it, and who can raise it.
    const std::string limit = std::to_string(max_compute_ms) + " ms";
    if (job.budget_ms > 0 &&
        job.budget_ms < static_cast<uint32_t>(max_compute_ms)) {
      return {grpc::StatusCode::DEADLINE_EXCEEDED,
              "the request's time limit (time_budget_ms " +
                  std::to_string(job.budget_ms) + " ms) passed (" + s.message +
                  "); raise it (dotctl --time-budget-ms) up to the server's " +
                  limit};
    }
    return {grpc::StatusCode::DEADLINE_EXCEEDED,
            "the server's compute time limit (" + limit + ") passed (" +
                s.message +
                "); only its operator can raise it (dot-server "
                "--max-compute-ms)"};
  }
  if (s.code != StatusCode::kOk && s.code != StatusCode::kNoTriangulation) {
    return wire::ToGrpcStatus(s);
  }
  return grpc::Status::OK;
}

JobResponse::JobResponse(std::shared_ptr<const Job> job, size_t chunk_bytes,
                         int max_compute_ms)
    : job_(std::move(job)),
      status_(JobStatus(*job_, max_compute_ms)),
      chunks_(
          job_->result,
          job_->wire.omit_input_vertices() ? job_->problem.vertices.size() : 0,
          chunk_bytes) {
  done_ = !status_.ok();
}

bool JobResponse::Next(v1::TriangulateResponse* message) {
  if (done_) return false;
  message->Clear();
  message->set_id(job_->id);
  if (chunks_.Next(message->mutable_mesh())) return true;
  v1::Summary* summary = message->mutable_summary();
  wire::FillSummary(job_->result, summary);
  summary->set_queue_ms(Ms(job_->started - job_->arrived));
  summary->set_compute_ms(Ms(job_->finished - job_->started));
  done_ = true;
  return true;
}

}  // namespace dot::server
