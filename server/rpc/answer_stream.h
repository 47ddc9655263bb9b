// SPDX-License-Identifier: AGPL-3.0-or-later
// The write side every "progress while the job runs, then the answer"
// stream shares (Triangulate, FillHoles), as a base for its reactor: the
// progress reports (AnswerWriter decides when one may go), the answer's
// messages once the job is done (the reactor makes them: NextAnswer),
// finishing exactly once, and the answered call's log line and metrics in
// OnDone. `Base` is the gRPC reactor (write-only or bidirectional); messages
// go out serialized as raw bytes.
#ifndef DOT_SERVER_RPC_ANSWER_STREAM_H_
#define DOT_SERVER_RPC_ANSWER_STREAM_H_

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>

#include "rpc/answer_writer.h"
#include "rpc/job.h"
#include "rpc/job_response.h"
#include "rpc/raw_message.h"

namespace dot::server {

template <class Base, class Response>
class AnswerStream : public Base {
 public:
  void OnWriteDone(bool ok) override {
    switch (
        writer_.WriteDone(ok, job_.get(), [this] { message_.Swap(&kept_); })) {
      case AnswerWriter::Next::kKept:  // a forced report that waited
        Write(false);
        break;
      case AnswerWriter::Next::kAnswer:
        WriteNext();
        break;
      case AnswerWriter::Next::kNothing:
        break;
    }
  }
  void OnDone() override {
    // StartWriteAndFinish reports no failed write: ask the context.
    if (final_status_.ok() && context_->IsCancelled()) {
      if (job_->stop == StopReason::kNone) {
        job_->StopForCancel(context_->deadline());
      }
      final_status_ = StoppedStatus(job_->stop);
    }
    runner_->Answered(*job_, final_status_);
    delete this;  // gRPC's callback API: a reactor owns itself until OnDone
  }

 protected:
  AnswerStream(JobRunner* runner, grpc::CallbackServerContext* context)
      : runner_(runner), context_(context) {}

  // Once the job is done, with the right to write: the next message of the
  // answer into `message`, or a status (not OK, `*last` unset) that ends the
  // call instead. `*last` marks the final message; the status returned with
  // it is the one the call ends with (a partial answer's is not OK).
  virtual grpc::Status NextAnswer(Response* message, bool* last) = 0;

  // The job's on_done (on the computing thread).
  void JobDone() {
    if (writer_.JobDone()) WriteNext();
  }
  // From the computing thread: writes the progress report `fill` makes,
  // unless one is in flight or younger than `interval`. A `force`d report
  // (a new phase, the last hole) ignores the interval and, when a write is
  // in flight, is kept to go right after it (before the answer), unless a
  // newer kept report replaces it.
  template <class Fill>
  void WriteProgress(Clock::duration interval, bool force, const Fill& fill) {
    const auto keep = [&] {
      kept_.Clear();
      kept_.set_id(job_->id);
      fill(&kept_);
    };
    if (!writer_.ClaimProgress(interval, force, keep)) return;
    message_.Clear();
    message_.set_id(job_->id);
    fill(&message_);
    Write(false);
  }
  // Finishes the call with `status` unless it is finished already.
  void FinishWith(const grpc::Status& status) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (finished_) return;
      finished_ = true;
    }
    FinishClaimed(status);
  }
  // Finishes the call; the caller has set finished_ under mu_.
  void FinishClaimed(const grpc::Status& status) {
    writer_.Close();
    final_status_ = status;
    this->Finish(status);
  }

  JobRunner* const runner_;
  grpc::CallbackServerContext* const context_;
  std::shared_ptr<Job> job_;  // set before the job starts
  grpc::Status final_status_;
  // Guards finished_, and whatever a reactor decides together with it.
  std::mutex mu_;
  bool finished_ = false;

 private:
  // Only ever called by whoever holds the (single) right to write.
  void WriteNext() {
    if (writer_.broken()) {
      FinishWith(StoppedStatus(job_->stop));
      return;
    }
    bool last = false;
    const grpc::Status status = NextAnswer(&message_, &last);
    if (!status.ok() && !last) {
      FinishWith(status);
      return;
    }
    if (last) {
      std::lock_guard<std::mutex> lock(mu_);
      if (finished_) return;
      finished_ = true;
      final_status_ = status;
    }
    Write(last);
  }
  void Write(bool last) {
    SerializeRaw(message_, &bytes_);
    if (last) {
      this->StartWriteAndFinish(&bytes_, grpc::WriteOptions(), final_status_);
    } else {
      this->StartWrite(&bytes_);
    }
  }

  AnswerWriter writer_;
  Response message_;        // the message being written
  Response kept_;           // a forced report waiting (under writer_'s lock)
  grpc::ByteBuffer bytes_;  // message_, serialized
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_ANSWER_STREAM_H_
