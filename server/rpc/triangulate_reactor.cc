// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/triangulate_reactor.h"

#include "rpc/raw_message.h"

namespace dot::server {

TriangulateReactor::TriangulateReactor(JobRunner* runner,
                                       grpc::CallbackServerContext* context,
                                       grpc::ByteBuffer bytes)
    : runner_(runner), context_(context) {
  v1::TriangulateRequest request;
  if (!ParseRaw(&bytes, &request)) {
    job_ = std::make_shared<Job>();  // not admitted: answered and logged
    job_->rpc = "Triangulate";
    job_->arrived = Clock::now();
    FinishWith(UnparsableRequest("Triangulate", "TriangulateRequest"));
    return;
  }
  grpc::Status refused;
  job_ = runner_->Admit(request, context->deadline(), "Triangulate", &refused);
  if (!refused.ok()) {
    FinishWith(refused);
    return;
  }
  const auto interval_ms = job_->wire.progress_interval_ms();
  if (interval_ms > 0) {
    job_->on_progress = [this](const v1::Progress& p) { OnProgress(p); };
  }
  job_->on_done = [this] { OnJobDone(); };
  // Small Delaunay-space calls without progress skip the handoff to a
  // worker; 'all' can be slow at any size, so it always goes to the pool.
  const ServiceOptions& o = runner_->options();
  const bool small = interval_ms == 0 &&
                     job_->options.space != SearchSpace::kAll &&
                     job_->problem.vertices.size() <=
                         static_cast<size_t>(o.inline_max_vertices);
  if (!runner_->Start(job_, small)) FinishWith(runner_->Overloaded());
}

void TriangulateReactor::OnProgress(const v1::Progress& progress) {
  // The next report comes within ~50 ms when this one is skipped.
  if (!writer_.ClaimProgress(
          std::chrono::milliseconds(job_->wire.progress_interval_ms()))) {
    return;
  }
  message_.Clear();
  message_.set_id(job_->id);
  *message_.mutable_progress() = progress;
  Write(false);
}

void TriangulateReactor::OnJobDone() {
  if (writer_.JobDone()) WriteNext();
}

void TriangulateReactor::OnWriteDone(bool ok) {
  if (writer_.WriteDone(ok, job_.get())) WriteNext();
}

void TriangulateReactor::WriteNext() {
  if (writer_.broken()) {
    FinishWith(StoppedStatus(StopReason::kClientGone));
    return;
  }
  if (!response_) {
    const ServiceOptions& o = runner_->options();
    response_.emplace(job_, o.chunk_bytes, o.max_compute_ms);
  }
  if (!response_->status().ok()) {
    FinishWith(response_->status());
    return;
  }
  response_->Next(&message_);
  if (response_->done()) final_status_ = grpc::Status::OK;
  Write(response_->done());
}

void TriangulateReactor::Write(bool last) {
  SerializeRaw(message_, &message_bytes_);
  if (last) {
    StartWriteAndFinish(&message_bytes_, grpc::WriteOptions(), final_status_);
  } else {
    StartWrite(&message_bytes_);
  }
}

void TriangulateReactor::FinishWith(const grpc::Status& status) {
  final_status_ = status;
  Finish(status);
}

void TriangulateReactor::OnCancel() {
  if (job_) job_->StopForCancel(context_->deadline());
}

void TriangulateReactor::OnDone() {
  // StartWriteAndFinish reports no write failure: ask the context.
  if (final_status_.ok() && context_->IsCancelled()) {
    if (job_->stop == StopReason::kNone) {
      job_->StopForCancel(context_->deadline());
    }
    final_status_ = StoppedStatus(job_->stop);
  }
  runner_->Answered(*job_, final_status_);
  delete this;  // gRPC's callback API: a reactor owns itself until OnDone
}

}  // namespace dot::server
