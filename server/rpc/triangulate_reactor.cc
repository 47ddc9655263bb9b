// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/triangulate_reactor.h"

namespace dot::server {

TriangulateReactor::TriangulateReactor(JobRunner* runner,
                                       grpc::CallbackServerContext* context,
                                       grpc::ByteBuffer bytes)
    : AnswerStream(runner, context) {
  v1::TriangulateRequest request;
  if (!ParseRaw(&bytes, &request)) {
    job_ = runner_->Unadmitted("Triangulate", context->deadline());
    FinishWith(UnparsableRequest("Triangulate", "TriangulateRequest"));
    return;
  }
  grpc::Status refused;
  job_ = runner_->Admit(request, context->deadline(), "Triangulate", &refused);
  if (!refused.ok()) {
    FinishWith(refused);
    return;
  }
  const auto interval =
      std::chrono::milliseconds(job_->wire.progress_interval_ms());
  if (interval.count() > 0) {
    // The next report comes within ~50 ms when this one is skipped.
    job_->on_progress = [this, interval](const v1::Progress& p) {
      WriteProgress(interval, false,
                    [&](auto* m) { *m->mutable_progress() = p; });
    };
  }
  job_->on_done = [this] { JobDone(); };
  // Small Delaunay-space calls without progress skip the handoff to a
  // worker; 'all' and 'delaunay_first' can be slow at any size, so they
  // always go to the pool.
  const ServiceOptions& o = runner_->options();
  const bool small = interval.count() == 0 &&
                     job_->options.space != SearchSpace::kAll &&
                     job_->options.space != SearchSpace::kDelaunayFirst &&
                     job_->problem.vertices.size() <=
                         static_cast<size_t>(o.inline_max_vertices);
  if (!runner_->Start(job_, small)) FinishWith(runner_->Overloaded());
}

grpc::Status TriangulateReactor::NextAnswer(v1::TriangulateResponse* message,
                                            bool* last) {
  if (!response_) {
    const ServiceOptions& o = runner_->options();
    response_.emplace(job_, o.chunk_bytes, o.max_compute_ms);
  }
  if (!response_->status().ok()) return response_->status();
  response_->Next(message);
  *last = response_->done();
  return grpc::Status::OK;
}

void TriangulateReactor::OnCancel() {
  if (job_) job_->StopForCancel(context_->deadline());
}

}  // namespace dot::server
