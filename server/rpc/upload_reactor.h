// SPDX-License-Identifier: AGPL-3.0-or-later
// The transport of an RPC whose input streams in and whose work runs as
// one job (FillHoles, SurfaceNetwork): the first message admits the job
// and its options are checked once, each message is accepted by the use's
// Upload, the use's Call runs on the compute pool, and progress, the
// answer and its last message stream back (AnswerStream). The reactor
// finishes only after the job's on_done, so the job never outlives it.
//
// Messages travel raw (grpc::ByteBuffer) and are parsed here, so that a
// message that does not parse is an error naming its position, not an end
// of the upload. The upload is bounded by timers (UploadTimers), not by
// the client's next message.
//
// `Use` names the RPC's parts: Request, Response, Input (what the upload
// becomes), Upload (Add(request, job), Finish(input*), messages()), Call
// (Configure(options, server options, threads), partial(), done(),
// Next(id, chunk bytes, response*)), the strings kMethod ("FillHoles") and
// kInput ("mesh"), and
//   static Status Run(Call&, Input, Job&, const Control&, const Progress&)
// where Progress(force, fill) writes a progress message `fill` makes.
#ifndef DOT_SERVER_RPC_UPLOAD_REACTOR_H_
#define DOT_SERVER_RPC_UPLOAD_REACTOR_H_

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <string>

#include "rpc/answer_stream.h"
#include "rpc/job.h"
#include "rpc/upload_timers.h"
#include "wire/wire.h"

namespace dot::server {

template <class Use>
class UploadReactor final
    : public AnswerStream<
          grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>,
          typename Use::Response> {
  using Base =
      AnswerStream<grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>,
                   typename Use::Response>;

 public:
  // Writes a progress message that `fill` makes; `force` as AnswerStream's.
  using Progress = std::function<void(
      bool force, const std::function<void(typename Use::Response*)>& fill)>;

  UploadReactor(JobRunner* runner, grpc::CallbackServerContext* context)
      : Base(runner, context),
        upload_(runner),
        timers_([this] { OnUploadTimer(); }),
        unadmitted_(runner->Unadmitted(Use::kMethod, context->deadline())) {
    // A client that opens the stream and sends nothing holds it no longer
    // than the server's time limit (or its own deadline).
    timers_.FirstMessageBy(std::min(
        context->deadline(),
        std::chrono::system_clock::now() +
            std::chrono::milliseconds(runner->options().max_compute_ms)));
    this->StartRead(&request_);
  }

  void OnReadDone(bool ok) override {
    {
      std::lock_guard<std::mutex> lock(this->mu_);
      if (this->finished_) return;
      if (!ok) uploading_ = false;
    }
    if (!ok) {  // the client half-closed, or the call broke
      if (!this->context_->IsCancelled()) {
        StartWork();
      } else if (this->job_) {
        this->job_->StopForCancel(this->context_->deadline());
        this->FinishWith(StoppedStatus(this->job_->stop));
      } else {
        this->FinishWith(StoppedStatus(StopReason::kClientCancel));
      }
      return;
    }
    const grpc::Status s = Accept();
    if (!s.ok()) {
      this->FinishWith(s);
      return;
    }
    // Under the lock, so that a timer either finished the call before (no
    // read after Finish) or finds this read outstanding.
    std::lock_guard<std::mutex> lock(this->mu_);
    if (!this->finished_) this->StartRead(&request_);
  }

  void OnCancel() override {
    std::shared_ptr<Job> job;
    {
      std::lock_guard<std::mutex> lock(this->mu_);
      job = this->job_;
    }
    if (job) job->StopForCancel(this->context_->deadline());
  }

  void OnDone() override {
    timers_.Disarm();  // a timer firing now finds nobody
    if (!this->job_) {
      // The call ended before its first message was accepted: it is still
      // logged, and a stop counted by its reason.
      this->job_ = std::move(unadmitted_);
      this->job_->log_detail = "input=incomplete";
      if (this->context_->IsCancelled()) {
        this->job_->StopForCancel(this->context_->deadline());
        this->final_status_ = StoppedStatus(this->job_->stop);
      } else if (this->final_status_.error_code() ==
                 grpc::StatusCode::DEADLINE_EXCEEDED) {
        this->job_->StopAtDeadline();
      }
    }
    Base::OnDone();
  }

 private:
  static constexpr auto kProgressInterval = std::chrono::milliseconds(250);

  // One message of the upload; not OK ends the call with that status.
  grpc::Status Accept() {
    typename Use::Request m;
    if (!ParseRaw(&request_, &m)) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "message " + std::to_string(upload_.messages()) +
                  " of the upload does not parse as a " +
                  m.GetDescriptor()->name()};
    }
    if (!this->job_) {
      const grpc::Status admitted = Admit(m);
      if (!admitted.ok()) return admitted;
    }
    const grpc::Status s = upload_.Add(m, *this->job_);
    std::lock_guard<std::mutex> lock(this->mu_);
    messages_read_ = upload_.messages();
    return s;
  }

  // The first message: the job admitted, its options checked once.
  grpc::Status Admit(const typename Use::Request& first) {
    grpc::Status refused;
    auto job = this->runner_->AdmitTask(Use::kMethod, first.id(),
                                        first.options().time_budget_ms(),
                                        this->context_->deadline(), &refused);
    job->log_detail = "input=incomplete";  // until the work says more
    {
      std::lock_guard<std::mutex> lock(this->mu_);
      this->job_ = std::move(job);
    }
    if (!refused.ok()) return refused;
    timers_.UploadBy(this->job_->deadline);
    // Checked before the input is read, not after.
    const Status s = call_.Configure(first.options(), this->runner_->options(),
                                     this->runner_->compute_threads());
    if (!s.ok()) return wire::ToGrpcStatus(s);
    // A drain ends an unfinished upload at once (from a gRPC thread).
    this->runner_->SetOnDrain(this->job_.get(), [this] { timers_.FireNow(); });
    return grpc::Status::OK;
  }

  // The input did not arrive in time, or the server began to drain.
  void OnUploadTimer() {
    std::shared_ptr<Job> job;
    size_t messages = 0;
    {
      // The decision and the claim to finish are one step: a half-close
      // handled meanwhile (uploading_ cleared) or an error answered first
      // (finished_) wins, and the timer does nothing.
      std::lock_guard<std::mutex> lock(this->mu_);
      if (!uploading_ || this->finished_) return;
      this->finished_ = true;
      uploading_ = false;
      job = this->job_;
      messages = messages_read_;
    }
    if (job && this->runner_->draining() && Clock::now() < job->deadline) {
      job->Stop(StopReason::kDrain);
    } else if (job) {  // without a job, OnDone counts the stop
      job->StopAtDeadline();
    }
    this->FinishClaimed(
        job && job->stop == StopReason::kDrain
            ? StoppedStatus(StopReason::kDrain)
            : grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                           std::string("the ") + Use::kInput +
                               " did not arrive within the time limit (" +
                               std::to_string(messages) +
                               " messages arrived, and no end of the "
                               "upload)"));
  }

  // The upload is complete: the work is queued.
  void StartWork() {
    const Status s = upload_.Finish(&input_);
    if (!s.ok() || !this->job_) {
      this->FinishWith(wire::ToGrpcStatus(
          s.ok()
              ? InvalidArgument(std::string("no ") + Use::kInput + " was sent")
              : s));
      return;
    }
    this->job_->on_done = [this] { this->JobDone(); };
    const auto work = [this](Job& job, const Control& control) {
      const Progress progress = [this](bool force, const auto& fill) {
        this->WriteProgress(kProgressInterval, force, fill);
      };
      return Use::Run(call_, std::move(input_), job, control, progress);
    };
    if (!this->runner_->Start(this->job_, /*may_run_here=*/false, work)) {
      this->job_->on_done = nullptr;
      this->FinishWith(this->runner_->Overloaded());
    }
  }

  grpc::Status NextAnswer(typename Use::Response* message,
                          bool* last) override {
    const grpc::Status status =
        JobStatus(*this->job_, this->runner_->options().max_compute_ms);
    // Work stopped by a limit or a drain answers what it kept, then its
    // status; a client that left or cancelled is not written to.
    if (!status.ok() && !(call_.partial() && this->job_->ClientWaits())) {
      return status;
    }
    call_.Next(this->job_->id, this->runner_->options().chunk_bytes, message);
    *last = call_.done();
    return *last ? status : grpc::Status::OK;
  }

  typename Use::Upload upload_;
  typename Use::Call call_;    // touched by the compute thread while it runs
  typename Use::Input input_;  // moved into the work
  grpc::ByteBuffer request_;   // the read in flight
  bool uploading_ = true;      // under mu_: reads go on, the timers may end it
  size_t messages_read_ = 0;   // under mu_: for the timers' message
  UploadTimers timers_;
  // What is logged if no first message is accepted: made when the call
  // arrives, so its latency and deadline are the call's own.
  std::shared_ptr<Job> unadmitted_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_UPLOAD_REACTOR_H_
