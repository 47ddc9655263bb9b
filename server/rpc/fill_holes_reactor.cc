// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/fill_holes_reactor.h"

#include <algorithm>

namespace dot::server {
namespace {
constexpr auto kProgressInterval = std::chrono::milliseconds(250);
}  // namespace

FillHolesReactor::FillHolesReactor(JobRunner* runner,
                                   grpc::CallbackServerContext* context)
    : AnswerStream(runner, context),
      upload_(runner),
      timers_([this] { OnUploadTimer(); }),
      unadmitted_(runner->Unadmitted("FillHoles", context->deadline())) {
  // A client that opens the stream and sends nothing holds it no longer
  // than the server's time limit (or its own deadline).
  timers_.FirstMessageBy(std::min(
      context_->deadline(),
      std::chrono::system_clock::now() +
          std::chrono::milliseconds(runner->options().max_compute_ms)));
  StartRead(&request_);
}

void FillHolesReactor::OnReadDone(bool ok) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (finished_) return;
    if (!ok) uploading_ = false;
  }
  if (!ok) {  // the client half-closed, or the call broke
    if (!context_->IsCancelled()) {
      StartFill();
    } else if (job_) {
      job_->StopForCancel(context_->deadline());
      FinishWith(StoppedStatus(job_->stop));
    } else {
      FinishWith(StoppedStatus(StopReason::kClientCancel));
    }
    return;
  }
  const grpc::Status s = Accept();
  if (!s.ok()) {
    FinishWith(s);
    return;
  }
  // Under the lock, so that a timer either finished the call before (no
  // read after Finish) or finds this read outstanding.
  std::lock_guard<std::mutex> lock(mu_);
  if (!finished_) StartRead(&request_);
}

grpc::Status FillHolesReactor::Accept() {
  v1::FillHolesRequest m;
  if (!ParseRaw(&request_, &m)) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            "message " + std::to_string(upload_.messages()) +
                " of the upload does not parse as a FillHolesRequest"};
  }
  if (!job_) {
    const grpc::Status admitted = Admit(m);
    if (!admitted.ok()) return admitted;
  }
  const grpc::Status s = upload_.Add(m, *job_);
  std::lock_guard<std::mutex> lock(mu_);
  messages_read_ = upload_.messages();
  return s;
}

grpc::Status FillHolesReactor::Admit(const v1::FillHolesRequest& first) {
  grpc::Status refused;
  auto job = runner_->AdmitTask("FillHoles", first.id(),
                                first.options().time_budget_ms(),
                                context_->deadline(), &refused);
  job->log_detail = "input=incomplete";  // until the fill says more
  {
    std::lock_guard<std::mutex> lock(mu_);
    job_ = std::move(job);
  }
  if (!refused.ok()) return refused;
  timers_.UploadBy(job_->deadline);
  // Checked before the mesh is read, not after.
  const Status s = call_.Configure(first.options(), runner_->options(),
                                   runner_->compute_threads());
  if (!s.ok()) return wire::ToGrpcStatus(s);
  // A drain ends an unfinished upload at once (from a gRPC thread).
  runner_->SetOnDrain(job_.get(), [this] { timers_.FireNow(); });
  return grpc::Status::OK;
}

void FillHolesReactor::OnUploadTimer() {
  std::shared_ptr<Job> job;
  size_t messages = 0;
  {
    // The decision and the claim to finish are one step: a half-close
    // handled meanwhile (uploading_ cleared) or an error answered first
    // (finished_) wins, and the timer does nothing.
    std::lock_guard<std::mutex> lock(mu_);
    if (!uploading_ || finished_) return;
    finished_ = true;
    uploading_ = false;
    job = job_;
    messages = messages_read_;
  }
  if (job && runner_->draining() && Clock::now() < job->deadline) {
    job->Stop(StopReason::kDrain);
  } else if (job) {  // without a job, OnDone counts the stop
    job->StopAtDeadline();
  }
  FinishClaimed(
      job && job->stop == StopReason::kDrain
          ? StoppedStatus(StopReason::kDrain)
          : grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                         "the mesh did not arrive within the time limit (" +
                             std::to_string(messages) +
                             " messages arrived, and no end of the upload)"));
}

void FillHolesReactor::StartFill() {
  const Status s = upload_.Finish(&soup_);
  if (!s.ok() || !job_) {
    FinishWith(
        wire::ToGrpcStatus(s.ok() ? InvalidArgument("no mesh was sent") : s));
    return;
  }
  job_->on_done = [this] { JobDone(); };
  const auto fill = [this](Job& job, const Control& job_control) {
    wire::FillProgressClock clock(job.arrived);
    Control control = job_control;  // a stopped fill's holes are kept
    control.keep_partial = [&job] { return job.ClientWaits(); };
    return call_.Run(
        std::move(soup_), control,
        [this, &clock](FillPhase phase, int done, int total) {
          // A new phase, and the last hole, are always reported.
          const bool force =
              phase != FillPhase::kHoles || done == total || done == 0;
          WriteProgress(kProgressInterval, force, [&](auto* m) {
            *m->mutable_progress() = clock.Report(phase, done, total);
          });
        },
        &job.log_detail);
  };
  if (!runner_->Start(job_, /*may_run_here=*/false, fill)) {
    job_->on_done = nullptr;
    FinishWith(runner_->Overloaded());
  }
}

grpc::Status FillHolesReactor::NextAnswer(v1::FillHolesResponse* message,
                                          bool* last) {
  const grpc::Status status =
      JobStatus(*job_, runner_->options().max_compute_ms);
  // A fill stopped by a limit or a drain answers what it kept, then its
  // status; a client that left or cancelled is not written to.
  if (!status.ok() && !(call_.partial() && job_->ClientWaits())) return status;
  call_.Next(job_->id, runner_->options().chunk_bytes, message);
  *last = call_.done();
  return *last ? status : grpc::Status::OK;
}

void FillHolesReactor::OnCancel() {
  std::shared_ptr<Job> job;
  {
    std::lock_guard<std::mutex> lock(mu_);
    job = job_;
  }
  if (job) job->StopForCancel(context_->deadline());
}

void FillHolesReactor::OnDone() {
  timers_.Disarm();  // a timer firing now finds nobody
  if (!job_) {
    // The call ended before its first message was accepted: it is still
    // logged, and a stop counted by its reason.
    job_ = std::move(unadmitted_);
    job_->log_detail = "input=incomplete";
    if (context_->IsCancelled()) {
      job_->StopForCancel(context_->deadline());
      final_status_ = StoppedStatus(job_->stop);
    } else if (final_status_.error_code() ==
               grpc::StatusCode::DEADLINE_EXCEEDED) {
      job_->StopAtDeadline();
    }
  }
  AnswerStream::OnDone();
}

}  // namespace dot::server
