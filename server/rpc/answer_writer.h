// SPDX-License-Identifier: AGPL-3.0-or-later
// The write side of a stream that reports progress while its job runs,
// then writes the answer (Triangulate, FillHoles): one write in flight at a
// time, progress only while the job runs and at most once per interval,
// and whoever holds the right to write when the job ends writes the answer.
// A failed write means the client is gone: the job is stopped. The reactor
// owns the messages and the gRPC calls; this decides who may write when.
#ifndef DOT_SERVER_RPC_ANSWER_WRITER_H_
#define DOT_SERVER_RPC_ANSWER_WRITER_H_

#include <mutex>

#include "rpc/job.h"

namespace dot::server {

class AnswerWriter {
 public:
  // From the computing thread: true when a progress report may be written
  // now (the caller writes it; its completion comes to WriteDone). False:
  // skip this one (a write is in flight, the job has ended, the call is
  // closed, or the last report is younger than `interval`, unless `force`).
  bool ClaimProgress(Clock::duration interval, bool force = false) {
    std::lock_guard<std::mutex> lock(mu_);
    const auto now = Clock::now();
    if (writing_ || job_done_ || broken_ || closed_ ||
        (!force && now - last_progress_ < interval)) {
      return false;
    }
    last_progress_ = now;
    writing_ = true;
    return true;
  }
  // The job's on_done: true when the caller now holds the right to write
  // and must write the answer; false when a write in flight will hand it
  // over through WriteDone.
  bool JobDone() {
    std::lock_guard<std::mutex> lock(mu_);
    job_done_ = true;
    if (writing_) return false;
    writing_ = true;
    return true;
  }
  // OnWriteDone: true when the caller holds the right to write the next
  // message of the answer (or to finish, when broken()).
  bool WriteDone(bool ok, Job* job) {
    std::lock_guard<std::mutex> lock(mu_);
    if (!ok) {
      broken_ = true;
      if (job != nullptr) job->Stop(StopReason::kClientGone);
    }
    if (!job_done_) {  // a progress report; the job carries on
      writing_ = false;
      return false;
    }
    return true;
  }
  // A write failed: the client is gone.
  bool broken() {
    std::lock_guard<std::mutex> lock(mu_);
    return broken_;
  }
  // The call is being finished: no progress report is written after this.
  void Close() {
    std::lock_guard<std::mutex> lock(mu_);
    closed_ = true;
  }

 private:
  std::mutex mu_;
  bool writing_ = false;   // a write is in flight
  bool job_done_ = false;  // on_done has run
  bool broken_ = false;    // a write failed
  bool closed_ = false;    // the reactor finishes the call
  Clock::time_point last_progress_{};
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_ANSWER_WRITER_H_
