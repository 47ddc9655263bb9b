// SPDX-License-Identifier: AGPL-3.0-or-later
// One call's life in the service, shared by every RPC: admission (drain,
// id, deadline; a polygon's shape and limits), a run on the compute pool or
// inline, and the completion callback that hands the result back to the
// RPC's reactor. A reactor answers its job only after the job's
// on_done has run, so a job never outlives the reactor it calls.
#ifndef DOT_SERVER_RPC_JOB_H_
#define DOT_SERVER_RPC_JOB_H_

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <string_view>

#include "compute/compute_pool.h"
#include "dot/delaunay_helpers.h"
#include "dot/space_cache.h"
#include "dot/triangulate.h"
#include "dot/v1/triangulation.pb.h"
#include "rpc/service_options.h"
#include "server_metrics.h"

namespace dot::server {

using Clock = std::chrono::steady_clock;

// Request ids are echoed in every response and logged: keep them short.
inline constexpr size_t kMaxRequestIdBytes = 256;

// Why a job was stopped before it finished: logged, counted
// (dot_requests_stopped_total) and answered each its own way.
enum class StopReason {
  kNone,
  kClientCancel,    // the client cancelled the call
  kClientDeadline,  // the client's deadline passed
  kServerBudget,    // the server's compute limit or the request's budget
  kDrain,           // the server is shutting down
  kClientGone,      // a write to the client failed
};
std::string_view StopReasonName(StopReason r);  // "client_cancel", ...

struct Job {
  std::string rpc, id;
  Problem problem;
  Options options;
  v1::Options wire;
  Clock::time_point arrived, started, finished, deadline;
  bool deadline_is_limit = false;  // the server's limit, not the client's
  uint32_t budget_ms = 0;          // the request's own time budget; 0: none
  std::atomic<bool> cancel{false};
  std::atomic<StopReason> stop{StopReason::kNone};  // the first reason wins

  // Sets the cancel flag, recording why (unless a reason is already set).
  void Stop(StopReason why) {
    StopReason none = StopReason::kNone;
    stop.compare_exchange_strong(none, why);
    cancel = true;
  }
  // The job's deadline passed: stopped by whoever set it.
  void StopAtDeadline() {
    Stop(deadline_is_limit ? StopReason::kServerBudget
                           : StopReason::kClientDeadline);
  }
  // The reason a gRPC OnCancel means: the client's deadline if it has
  // passed, else the client's cancel. The server's view of the deadline is
  // the client's timeout counted from when the call arrived, so it falls a
  // little after the client's own: the client's cancel at its deadline
  // arrives first. A cancel within kDeadlineSlack of it counts as the
  // deadline.
  void StopForCancel(std::chrono::system_clock::time_point client_deadline) {
    constexpr auto kDeadlineSlack = std::chrono::milliseconds(500);
    Stop(std::chrono::system_clock::now() + kDeadlineSlack >= client_deadline
             ? StopReason::kClientDeadline
             : StopReason::kClientCancel);
  }

  // Whether the client still waits for an answer: not once it cancelled,
  // its deadline passed or a write to it failed (a limit or a drain stops
  // the job, not the client).
  bool ClientWaits() const {
    const StopReason why = stop;
    return why != StopReason::kClientCancel &&
           why != StopReason::kClientDeadline && why != StopReason::kClientGone;
  }

  // Written by the computing thread before on_done; read after it.
  bool ran = false;
  Result result;
  // For calls that are not one polygon (FillHoles): what the log line
  // says instead of the polygon's size, weights, space and triangles.
  std::string log_detail;

  // Both run on the computing thread. on_done is the job's last act.
  std::function<void(const v1::Progress&)> on_progress;
  std::function<void()> on_done;
  // Set through JobRunner::SetOnDrain.
  std::function<void()> on_drain;
};

class JobRunner {
 public:
  // `helpers` null: TetGen in-process; `cache` null: no search-space cache.
  JobRunner(const ServiceOptions& options, ComputePool* pool,
            DelaunayHelperPool* helpers, SpaceCache* cache,
            ServerMetrics* metrics);

  // Admission, one path for every call: drain, id, the deadline (the
  // smallest of the server's limit, `budget_ms` and the client's RPC
  // `deadline`), then tracking for drains once every check has passed.
  // When `error` is not OK the job was refused and must not be started; it
  // is still answered (Answered) so the refusal is counted and logged. For
  // calls that are not one polygon (FillHoles), which set log_detail
  // themselves.
  std::shared_ptr<Job> AdmitTask(const char* rpc, const std::string& id,
                                 uint32_t budget_ms,
                                 std::chrono::system_clock::time_point deadline,
                                 grpc::Status* error);
  // A job for a call refused before admission (its message did not parse,
  // or never came): never started nor tracked, only Answered, so the call
  // is still logged and counted. Its deadline is set as AdmitTask's would be.
  std::shared_ptr<Job> Unadmitted(
      const char* rpc, std::chrono::system_clock::time_point deadline) const;
  // AdmitTask, then the polygon's own checks (shape, size) and the
  // request's memory budget under the server's.
  std::shared_ptr<Job> Admit(const v1::TriangulateRequest& request,
                             std::chrono::system_clock::time_point deadline,
                             const char* rpc, grpc::Status* error);

  // What a job computes, on the compute thread, with the job's Control
  // (cancel, deadline, progress, TetGen and large solves in the helpers);
  // its status lands in job.result.status.
  using Work = std::function<Status(Job& job, const Control& control)>;
  // Runs `work` (empty: Triangulate the job's polygon, with the cache
  // unless the request says no_cache), then job->on_done: inline on this
  // thread when `may_run_here` and a compute slot is free (on_done has then
  // run when this returns), else queued, polygons by size in the small or
  // large lane, other work in the large one. False when the queue is full:
  // the work never runs, on_done is not called.
  bool Start(const std::shared_ptr<Job>& job, bool may_run_here,
             Work work = {});
  // The status of a Start that returned false.
  grpc::Status Overloaded() const;

  // Counts a job's RPC (or batch item) answered, exactly once per Admit:
  // metrics and one log line.
  void Answered(const Job& job, const grpc::Status& status);

  // New jobs are refused with UNAVAILABLE from now on, and every admitted
  // job's on_drain runs (calls still uploading end at once: their clients
  // retry elsewhere).
  void StartDraining();
  // Sets job->on_drain, called at most once, with the runner's lock held:
  // it must only schedule work, never finish a call itself.
  void SetOnDrain(Job* job, std::function<void()> on_drain);
  // Cancels every admitted job; their RPCs answer UNAVAILABLE.
  void CancelAllForDrain();
  int inflight() const { return inflight_; }
  bool draining() const { return draining_; }

  // FillHoles memory: a call charges what it holds before holding it
  // (FillMemoryBytes of what it has sent); false, charging nothing, when
  // all calls together would exceed options().fill_memory_bytes.
  bool ChargeFillMemory(int64_t bytes);
  void ReleaseFillMemory(int64_t bytes);

  int compute_threads() const { return pool_->threads(); }
  int queue_capacity() const { return pool_->capacity(); }
  const ServiceOptions& options() const { return options_; }

 private:
  // The checks every call shares (drain, id, deadline); not tracked yet.
  std::shared_ptr<Job> NewJob(const char* rpc, const std::string& id,
                              uint32_t budget_ms,
                              std::chrono::system_clock::time_point deadline,
                              grpc::Status* error);
  static grpc::Status ShuttingDown();
  void Run(Job& job, const Work& work);
  Work TriangulateWork();
  // The Control every computation of `job` runs under.
  Control ControlFor(Job& job);
  // Gives memory freed beyond options_.malloc_keep_bytes back to the kernel.
  void ReturnFreedMemory();
  // False when draining began: the job is then refused, not tracked, so a
  // drain's CancelAllForDrain never misses a job admitted after it began.
  bool Track(Job* job);
  void Untrack(const Job* job);

  const ServiceOptions& options_;
  ComputePool* pool_;
  DelaunayHelperPool* helpers_;
  SpaceCache* cache_;
  ServerMetrics* metrics_;
  std::atomic<bool> draining_{false};
  std::atomic<int> inflight_{0};
  std::atomic<int64_t> fill_memory_{0};
  std::mutex jobs_mu_;
  std::set<Job*> jobs_;  // admitted and not yet answered
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_JOB_H_
