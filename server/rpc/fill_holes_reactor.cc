// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/fill_holes_reactor.h"

#include <algorithm>

#include "rpc/job_response.h"
#include "rpc/raw_message.h"

namespace dot::server {
namespace {

constexpr auto kProgressInterval = std::chrono::milliseconds(250);

// `t`, a steady-clock time, on the system clock gRPC's timers use.
std::chrono::system_clock::time_point ToSystem(Clock::time_point t) {
  return std::chrono::system_clock::now() +
         std::chrono::duration_cast<std::chrono::system_clock::duration>(
             t - Clock::now());
}

}  // namespace

FillHolesReactor::FillHolesReactor(JobRunner* runner,
                                   grpc::CallbackServerContext* context)
    : runner_(runner),
      context_(context),
      upload_(runner),
      timer_guard_(std::make_shared<TimerGuard>()) {
  timer_guard_->reactor = this;
  // A client that opens the stream and sends nothing holds it no longer
  // than the server's time limit (or its own deadline).
  const auto limit =
      std::min(context_->deadline(),
               std::chrono::system_clock::now() +
                   std::chrono::milliseconds(runner->options().max_compute_ms));
  SetTimer(&first_message_timer_, limit);
  StartRead(&request_);
}

void FillHolesReactor::SetTimer(grpc::Alarm* timer,
                                std::chrono::system_clock::time_point when) {
  timer->Set(when, [guard = timer_guard_](bool fired) {
    std::lock_guard<std::mutex> lock(guard->mu);
    if (fired && guard->reactor) guard->reactor->OnUploadTimer();
  });
}

void FillHolesReactor::OnReadDone(bool ok) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (finished_) return;
    if (!ok) uploading_ = false;
  }
  if (!ok) {
    // The client half-closed, or the call broke.
    if (context_->IsCancelled()) {
      if (job_) {
        job_->StopForCancel(context_->deadline());
        FinishWith(StoppedStatus(job_->stop));
      } else {
        FinishWith(StoppedStatus(StopReason::kClientCancel));
      }
      return;
    }
    StartFill();
    return;
  }
  const grpc::Status s = Accept();
  if (!s.ok()) {
    FinishWith(s);
    return;
  }
  // Under the lock, so that a timer either finished the call before (no
  // read after Finish) or finds this read outstanding. gRPC runs the
  // reaction on its executor, never inline here.
  std::lock_guard<std::mutex> lock(mu_);
  if (!finished_) StartRead(&request_);
}

grpc::Status FillHolesReactor::Accept() {
  v1::FillHolesRequest m;
  if (!ParseRaw(&request_, &m)) {
    // Before: the upload ended there as if the client had half-closed, and
    // the partial mesh was filled and answered OK.
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
  first_message_timer_.Cancel();  // the job's deadline bounds it now
  // Options are checked before the mesh is read, not after, and once.
  Status s = wire::FillOptionsFromWire(first.options(), &options_);
  if (s.ok()) s = wire::FillAnswerFromWire(first.options(), &answer_);
  if (!s.ok()) return wire::ToGrpcStatus(s);
  ApplyServerLimits(runner_->options(), first.options().memory_budget_bytes(),
                    runner_->compute_threads(), &options_);
  SetTimer(&upload_timer_, ToSystem(job_->deadline));
  // A drain ends an unfinished upload at once (from a gRPC thread).
  runner_->SetOnDrain(job_.get(), [this] {
    SetTimer(&drain_timer_, std::chrono::system_clock::now());
  });
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
  grpc::Status status;
  if (job && job->stop == StopReason::kNone && Clock::now() < job->deadline &&
      runner_->draining()) {
    job->Stop(StopReason::kDrain);
  }
  if (job && job->stop == StopReason::kDrain) {
    status = StoppedStatus(StopReason::kDrain);
  } else {
    if (job) {
      job->Stop(job->deadline_is_limit ? StopReason::kServerBudget
                                       : StopReason::kClientDeadline);
    }
    status = {grpc::StatusCode::DEADLINE_EXCEEDED,
              "the mesh did not arrive within the time limit (" +
                  std::to_string(messages) +
                  " messages arrived, and no end of the upload)"};
  }
  final_status_ = status;
  Finish(status);
}

void FillHolesReactor::StartFill() {
  const Status s = upload_.Finish(&soup_);
  if (!s.ok() || !job_) {
    FinishWith(
        wire::ToGrpcStatus(s.ok() ? InvalidArgument("no mesh was sent") : s));
    return;
  }
  job_->on_done = [this] { OnJobDone(); };
  if (!runner_->Start(job_, /*may_run_here=*/false,
                      [this](Job& job, const Control& control) {
                        return Fill(job, control);
                      })) {
    job_->on_done = nullptr;
    FinishWith(runner_->Overloaded());
  }
}

Status FillHolesReactor::Fill(Job& job, const Control& control) {
  // What the log says if the fill stops before it has more to say.
  job.log_detail =
      "received_vertices=" + std::to_string(soup_.vertices.size()) +
      " received_faces=" + std::to_string(soup_.faces.size());
  const auto sent_vertices = static_cast<int64_t>(soup_.vertices.size());
  result_ = FillSoup(std::move(soup_), options_, control,
                     [this](int done, int total) { OnHole(done, total); });
  if (result_.fill.status.ok() && answer_ == v1::FILL_ANSWER_PATCHES) {
    patches_ = PatchesAsSent(result_, sent_vertices);
    result_.fill.mesh = {};  // the patches are the answer
  }
  const FillReport& r = result_.fill.report;
  if (result_.input_faces > 0) {
    job.log_detail = "vertices=" + std::to_string(result_.input_vertices) +
                     " faces=" + std::to_string(result_.input_faces) +
                     " holes=" + std::to_string(r.loops) +
                     " filled=" + std::to_string(r.filled) +
                     " added_faces=" + std::to_string(r.added_faces);
  }
  return result_.fill.status;
}

void FillHolesReactor::OnHole(int done, int total) {
  // The last hole's report is always written: the client sees done == total.
  if (!writer_.ClaimProgress(kProgressInterval, done == total)) return;
  message_.Clear();
  message_.set_id(job_->id);
  v1::FillProgress* p = message_.mutable_progress();
  p->set_holes_done(done);
  p->set_holes_total(total);
  p->set_elapsed_ms(Ms(Clock::now() - job_->arrived));
  Write(message_, false);
}

void FillHolesReactor::OnJobDone() {
  if (writer_.JobDone()) WriteNext();
}

void FillHolesReactor::OnWriteDone(bool ok) {
  if (writer_.WriteDone(ok, job_.get())) WriteNext();
}

void FillHolesReactor::WriteNext() {
  if (writer_.broken()) {
    FinishWith(StoppedStatus(job_->stop));
    return;
  }
  if (!chunks_) {
    const grpc::Status status =
        JobStatus(*job_, runner_->options().max_compute_ms);
    if (!status.ok()) {
      FinishWith(status);
      return;
    }
    const size_t bytes = runner_->options().chunk_bytes;
    chunks_.emplace(result_.fill.mesh.vertices, result_.fill.mesh.triangles, 0,
                    bytes);
    patch_writer_.emplace(patches_, bytes);
  }
  message_.Clear();
  message_.set_id(job_->id);
  if (chunks_->Next(message_.mutable_mesh()) ||
      patch_writer_->Next(message_.mutable_patch())) {
    Write(message_, false);
    return;
  }
  wire::FillReportToWire(result_.fill.report, result_.repair,
                         static_cast<size_t>(result_.input_vertices),
                         static_cast<size_t>(result_.input_faces),
                         message_.mutable_report());
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (finished_) return;
    finished_ = true;
  }
  final_status_ = grpc::Status::OK;
  Write(message_, true);
}

void FillHolesReactor::Write(const v1::FillHolesResponse& message, bool last) {
  SerializeRaw(message, &message_bytes_);
  if (last) {
    StartWriteAndFinish(&message_bytes_, grpc::WriteOptions(), final_status_);
  } else {
    StartWrite(&message_bytes_);
  }
}

void FillHolesReactor::FinishWith(const grpc::Status& status) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (finished_) return;
    finished_ = true;
    uploading_ = false;
  }
  writer_.Close();
  final_status_ = status;
  Finish(status);
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
  {
    std::lock_guard<std::mutex> lock(timer_guard_->mu);
    timer_guard_->reactor = nullptr;  // a timer firing now finds nobody
  }
  if (!job_) {
    // The call ended before its first message was accepted: it is still
    // logged, and a stop counted by its reason.
    grpc::Status ignored;
    job_ =
        runner_->AdmitTask("FillHoles", "", 0, context_->deadline(), &ignored);
    job_->log_detail = "input=incomplete";
    if (context_->IsCancelled()) {
      job_->StopForCancel(context_->deadline());
      final_status_ = StoppedStatus(job_->stop);
    } else if (final_status_.error_code() ==
               grpc::StatusCode::DEADLINE_EXCEEDED) {
      job_->Stop(job_->deadline_is_limit ? StopReason::kServerBudget
                                         : StopReason::kClientDeadline);
    }
  }
  if (final_status_.ok() && context_->IsCancelled()) {
    if (job_->stop == StopReason::kNone) job_->Stop(StopReason::kClientGone);
    final_status_ = StoppedStatus(job_->stop);
  }
  runner_->Answered(*job_, final_status_);
  delete this;  // gRPC's callback API: a reactor owns itself until OnDone
}

}  // namespace dot::server
