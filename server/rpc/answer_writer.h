// SPDX-License-Identifier: AGPL-3.0-or-later
// The write side of a stream that reports progress while its job runs,
// then writes the answer (Triangulate, FillHoles): one write in flight at a
// time, progress only while the job runs and at most once per interval,
// and whoever holds the right to write when the job ends writes the answer.
// A failed write means the client is gone: the job is stopped. The reactor
// owns the messages and the gRPC calls; this decides who may write when.
#ifndef DOT_SERVER_RPC_ANSWER_WRITER_H_
#define DOT_SERVER_RPC_ANSWER_WRITER_H_

#include <functional>
#include <mutex>

#include "rpc/job.h"

namespace dot::server {

class AnswerWriter {
 public:
  // From the computing thread: true when a progress report may be written
  // now (the caller writes it; its completion comes to WriteDone). False:
  // skip this one (the job has ended, the call is closed, or the last
  // report is younger than `interval`, unless `force`), or, when a write is
  // in flight, keep a forced one: `keep` runs under the writer's lock and
  // stores the report, which goes out right after that write (WriteDone
  // says kKept) unless a newer kept report replaces it.
  bool ClaimProgress(Clock::duration interval, bool force = false,
                     const std::function<void()>& keep = nullptr) {
    std::lock_guard<std::mutex> lock(mu_);
    const auto now = Clock::now();
    if (job_done_ || broken_ || closed_) return false;
    if (writing_) {
      if (force && keep) {
        keep();
        kept_ = true;
      }
      return false;
    }
    // The first report is never held back: the steady clock counts from
    // boot, so on a machine up for less than `interval` a zero start
    // would hold it (seen on a machine up for 20 minutes).
    if (!force && any_progress_ && now - last_progress_ < interval) {
      return false;
    }
    any_progress_ = true;
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
  enum class Next {
    kNothing,  // the right to write is given back: the job carries on
    kKept,     // write the kept report (`take` has moved it out)
    kAnswer,   // write the answer's next message, or finish if broken()
  };
  // OnWriteDone: what the caller, who keeps the right to write unless
  // kNothing, does next. `take` runs under the lock when kKept.
  Next WriteDone(bool ok, Job* job,
                 const std::function<void()>& take = nullptr) {
    std::lock_guard<std::mutex> lock(mu_);
    if (!ok) {
      broken_ = true;
      if (job != nullptr) job->Stop(StopReason::kClientGone);
    }
    const bool kept = kept_ && !broken_ && !closed_;
    kept_ = false;
    if (kept) {
      if (take) take();
      return Next::kKept;
    }
    if (!job_done_) {  // a progress report; the job carries on
      writing_ = false;
      return Next::kNothing;
    }
    return Next::kAnswer;
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
  bool writing_ = false;       // a write is in flight
  bool kept_ = false;          // a forced report waits for it (ClaimProgress)
  bool job_done_ = false;      // on_done has run
  bool broken_ = false;        // a write failed
  bool closed_ = false;        // the reactor finishes the call
  bool any_progress_ = false;  // a report was claimed
  Clock::time_point last_progress_{};
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_ANSWER_WRITER_H_
