// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/job.h"

#include <malloc.h>

#include <algorithm>
#include <exception>
#include <utility>

#include "dot/table_memory.h"
#include "rpc/request_log.h"
#include "wire/wire.h"

namespace dot::server {
namespace {

// The job's deadline: the smallest of the server's limit, the request's
// time budget and the client's RPC deadline.
void SetDeadline(const ServiceOptions& o, uint32_t budget_ms,
                 std::chrono::system_clock::time_point client_deadline,
                 Job* job) {
  const int64_t limit_ms = budget_ms > 0
                               ? std::min<int64_t>(budget_ms, o.max_compute_ms)
                               : o.max_compute_ms;
  job->deadline = job->arrived + std::chrono::milliseconds(limit_ms);
  job->deadline_is_limit = true;
  if (client_deadline == std::chrono::system_clock::time_point::max()) return;
  const auto left = client_deadline - std::chrono::system_clock::now();
  const auto steady =
      job->arrived + std::chrono::duration_cast<Clock::duration>(left);
  if (steady < job->deadline) {
    job->deadline = steady;
    job->deadline_is_limit = false;
  }
}

// A run the core stopped at the job's deadline was stopped by whoever set
// that deadline.
void NoteDeadline(Job& job) {
  if (job.result.status.code == StatusCode::kDeadlineExceeded) {
    job.StopAtDeadline();
  }
}

}  // namespace

JobRunner::JobRunner(const ServiceOptions& options, ComputePool* pool,
                     DelaunayHelperPool* helpers, SpaceCache* cache,
                     ServerMetrics* metrics)
    : options_(options),
      pool_(pool),
      helpers_(helpers),
      cache_(cache),
      metrics_(metrics) {}

std::shared_ptr<Job> JobRunner::NewJob(
    const char* rpc, const std::string& id, uint32_t budget_ms,
    std::chrono::system_clock::time_point client_deadline,
    grpc::Status* error) {
  auto job = std::make_shared<Job>();
  *error = grpc::Status::OK;
  job->rpc = rpc;
  job->arrived = Clock::now();
  job->options = options_.solve;
  if (draining_) {
    *error = ShuttingDown();
    return job;
  }
  if (id.size() > kMaxRequestIdBytes) {
    *error = grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          "request id has " + std::to_string(id.size()) +
                              " bytes; at most " +
                              std::to_string(kMaxRequestIdBytes) + " allowed");
    return job;
  }
  job->id = id;
  job->budget_ms = budget_ms;
  SetDeadline(options_, budget_ms, client_deadline, job.get());
  return job;
}

grpc::Status JobRunner::ShuttingDown() {
  return {grpc::StatusCode::UNAVAILABLE,
          "server is shutting down; retry on another replica"};
}

std::shared_ptr<Job> JobRunner::AdmitTask(
    const char* rpc, const std::string& id, uint32_t budget_ms,
    std::chrono::system_clock::time_point client_deadline,
    grpc::Status* error) {
  auto job = NewJob(rpc, id, budget_ms, client_deadline, error);
  if (error->ok() && !Track(job.get())) *error = ShuttingDown();
  return job;
}

std::shared_ptr<Job> JobRunner::Unadmitted(
    const char* rpc,
    std::chrono::system_clock::time_point client_deadline) const {
  auto job = std::make_shared<Job>();
  job->rpc = rpc;
  job->arrived = Clock::now();
  SetDeadline(options_, 0, client_deadline, job.get());
  return job;
}

std::shared_ptr<Job> JobRunner::Admit(
    const v1::TriangulateRequest& request,
    std::chrono::system_clock::time_point client_deadline, const char* rpc,
    grpc::Status* error) {
  auto job = NewJob(rpc, request.id(), request.options().time_budget_ms(),
                    client_deadline, error);
  job->wire = request.options();
  if (!error->ok()) return job;
  // The polygon's own checks; only a job that passes them is tracked.
  const Status shape =
      wire::ProblemFromRequest(request, &job->problem, &job->options);
  if (!shape.ok()) {
    *error = wire::ToGrpcStatus(shape);
    return job;
  }
  const size_t n = job->problem.vertices.size();
  if (n > static_cast<size_t>(options_.max_vertices)) {
    *error = grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                          "polygon has " + std::to_string(n) +
                              " vertices; this server accepts at most " +
                              std::to_string(options_.max_vertices));
    return job;
  }
  job->options.memory_budget_bytes =
      RequestMemoryBudget(options_, request.options().memory_budget_bytes());
  job->options.all_space_max_vertices = options_.solve.all_space_max_vertices;
  if (!Track(job.get())) *error = ShuttingDown();
  return job;
}

JobRunner::Work JobRunner::TriangulateWork() {
  return [this](Job& job, const Control& job_control) {
    Control control = job_control;
    if (!job.wire.no_cache()) control.space_cache = cache_;
    job.result = dot::Triangulate(job.problem, job.options, control);
    // Counted when the request got as far as a search space (several loops
    // do not use the cache).
    if (control.space_cache != nullptr && job.problem.loop_sizes.empty() &&
        job.result.space_used != SpaceUsed::kNone) {
      metrics_->CacheLookup(job.result.stats.cache_hit,
                            control.space_cache->counters());
    }
    return job.result.status;
  };
}

bool JobRunner::Track(Job* job) {
  std::lock_guard<std::mutex> lock(jobs_mu_);
  if (draining_) return false;
  jobs_.insert(job);
  ++inflight_;
  metrics_->inflight().Set(inflight_);
  return true;
}

void JobRunner::Untrack(const Job* job) {
  std::lock_guard<std::mutex> lock(jobs_mu_);
  if (jobs_.erase(const_cast<Job*>(job)) > 0) --inflight_;
  metrics_->inflight().Set(inflight_);
}

bool JobRunner::Start(const std::shared_ptr<Job>& job, bool may_run_here,
                      Work work) {
  if (!work) work = TriangulateWork();
  if (may_run_here &&
      pool_->TryRunHere([this, &job, &work] { Run(*job, work); })) {
    return true;
  }
  // Polygons by size; other work (a whole mesh) is large.
  const Lane lane =
      job->problem.vertices.empty() ||
              job->problem.vertices.size() >=
                  static_cast<size_t>(options_.large_lane_min_vertices)
          ? Lane::kLarge
          : Lane::kSmall;
  const bool queued = pool_->TrySubmit(
      [this, job, work = std::move(work)] { Run(*job, work); }, lane);
  metrics_->queue_depth().Set(pool_->queued());
  return queued;
}

grpc::Status JobRunner::Overloaded() const {
  return {grpc::StatusCode::RESOURCE_EXHAUSTED,
          "server at capacity: " + std::to_string(pool_->capacity()) +
              " requests already queued; retry later"};
}

Control JobRunner::ControlFor(Job& job) {
  Control control;
  control.cancel = &job.cancel;
  control.deadline = job.deadline;
  if (job.on_progress) {
    control.progress = [&job](Stage stage, double fraction) {
      v1::Progress p;
      p.set_stage(wire::ToWire(stage));
      p.set_fraction(fraction);
      p.set_elapsed_ms(Ms(Clock::now() - job.arrived));
      job.on_progress(p);
    };
  }
  // Every path to TetGen goes through the helper processes: a TetGen
  // assertion then fails one request, not the server. Without helpers
  // (--delaunay-helpers 0) TetGen is refused, never run in process.
  if (helpers_ == nullptr) {
    control.tetrahedralize = [](const std::vector<Vec3>&, Tetrahedralization*) {
      return InvalidArgument(
          "the tetgen Delaunay backend is off on this server (it runs only "
          "in helper processes, and --delaunay-helpers is 0): use cgal");
    };
  } else {
    control.tetrahedralize = [this, &job](const std::vector<Vec3>& points,
                                          Tetrahedralization* out) {
      const Status s =
          helpers_->Tetrahedralize(points, out, &job.cancel, job.deadline,
                                   job.options.memory_budget_bytes);
      metrics_->HelperStarts(helpers_->starts());
      return s;
    };
    // Large fairing systems too: a cancel kills the solve at once.
    control.solve_sparse = [this, &job](const SparseSystem& system,
                                        std::vector<double>* x) {
      const Status s =
          helpers_->SolveSparse(system, x, &job.cancel, job.deadline,
                                job.options.memory_budget_bytes);
      metrics_->HelperStarts(helpers_->starts());
      return s;
    };
  }
  return control;
}

void JobRunner::Run(Job& job, const Work& work) {
  job.started = Clock::now();
  metrics_->queue_depth().Set(pool_->queued());
  metrics_->busy_threads().Set(pool_->busy());
  if (job.cancel) {
    job.result.status =
        MakeStatus(StatusCode::kCancelled, "cancelled while queued");
  } else if (job.started >= job.deadline) {
    job.result.status = MakeStatus(StatusCode::kDeadlineExceeded,
                                   "deadline passed in the queue");
  } else {
    try {
      const Status status = work(job, ControlFor(job));
      job.result.status = status;
    } catch (const std::exception& e) {  // bad_alloc above all
      job.result = {};
      job.result.status =
          MakeStatus(StatusCode::kResourceExhausted,
                     std::string("computation failed: ") + e.what());
    }
  }
  job.finished = Clock::now();
  NoteDeadline(job);
  // Only after large work: the check walks the heap.
  const Stats& st = job.result.stats;
  if (job.problem.vertices.empty() ||
      st.estimated_bytes > options_.malloc_keep_bytes / 8 ||
      st.tetrahedra > 1000000 ||
      job.result.status.code == StatusCode::kResourceExhausted) {
    ReturnFreedMemory();
  }
  job.ran = true;
  // The slot is released after this returns; count it free already, so the
  // gauge does not stay up when this was the last job.
  metrics_->busy_threads().Set(std::max(0, pool_->busy() - 1));
  // Moved out first: a callback may hold the job, and must not outlive it.
  std::function<void()> done = std::move(job.on_done);
  done();
}

bool JobRunner::ChargeFillMemory(int64_t bytes) {
  int64_t held = fill_memory_.load();
  do {
    if (held + bytes > options_.fill_memory_bytes) return false;
  } while (!fill_memory_.compare_exchange_weak(held, held + bytes));
  return true;
}

void JobRunner::ReleaseFillMemory(int64_t bytes) { fill_memory_ -= bytes; }

std::string_view StopReasonName(StopReason r) {
  switch (r) {
    case StopReason::kNone:
      return "none";
    case StopReason::kClientCancel:
      return "client_cancel";
    case StopReason::kClientDeadline:
      return "client_deadline";
    case StopReason::kServerBudget:
      return "server_budget";
    case StopReason::kDrain:
      return "drain";
    case StopReason::kClientGone:
      return "client_gone";
  }
  return "?";
}

void JobRunner::ReturnFreedMemory() {
  const int64_t keep = options_.malloc_keep_bytes;
  if (keep <= 0) return;
  // The trim runs only when more than `keep` lies free: in malloc's lists
  // and in the core's kept tables (half each, see main.cc).
  const struct mallinfo2 info = ::mallinfo2();
  const auto tables = static_cast<int64_t>(TableCacheBytesHeld());
  if (static_cast<int64_t>(info.fordblks) + tables > keep) {
    ::malloc_trim(0);
    TrimTableCache(static_cast<size_t>(keep / 2));
  }
}

void JobRunner::Answered(const Job& job, const grpc::Status& status) {
  Untrack(&job);
  LogRequest(job, status, metrics_);
}

void JobRunner::StartDraining() {
  std::lock_guard<std::mutex> lock(jobs_mu_);
  draining_ = true;
  for (Job* job : jobs_) {
    if (job->on_drain) std::exchange(job->on_drain, nullptr)();
  }
}

void JobRunner::SetOnDrain(Job* job, std::function<void()> on_drain) {
  std::lock_guard<std::mutex> lock(jobs_mu_);
  if (draining_) {
    on_drain();
  } else {
    job->on_drain = std::move(on_drain);
  }
}

void JobRunner::CancelAllForDrain() {
  std::lock_guard<std::mutex> lock(jobs_mu_);
  for (Job* job : jobs_) job->Stop(StopReason::kDrain);
}

}  // namespace dot::server
