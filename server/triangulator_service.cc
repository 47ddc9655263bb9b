// SPDX-License-Identifier: AGPL-3.0-or-later
#include "triangulator_service.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include "wire/wire.h"

#ifndef DOT_VERSION
#define DOT_VERSION "unknown"
#endif
#ifndef DOT_BUILD_INFO
#define DOT_BUILD_INFO "unknown"
#endif

namespace dot::server {
namespace {

using Clock = std::chrono::steady_clock;

double Ms(Clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

std::string WeightsLabel(const MetricWeights& w) {
  std::ostringstream s;
  for (Metric m : kAllMetrics) {
    if (w[m] == 0) continue;
    if (s.tellp() > 0) s << ',';
    s << MetricName(m) << '=' << w[m];
  }
  return s.tellp() > 0 ? s.str() : "area=1";
}

}  // namespace

// One polygon's life: prepared on the RPC thread, run on a compute thread.
struct TriangulatorService::Job {
  std::string rpc, id;
  Problem problem;
  Options options;
  v1::Options wire;
  std::atomic<bool> cancel{false};
  Clock::time_point arrived, started, finished, deadline;
  bool deadline_is_limit = false;  // the server's limit, not the client's

  std::mutex mu;
  std::condition_variable cv;
  bool done = false;
  Result result;
  bool has_progress = false;
  v1::Progress progress;
  std::function<void()> on_done;  // batches: wake the writer
};

TriangulatorService::TriangulatorService(ServiceLimits limits,
                                         ComputePool* pool,
                                         DelaunayHelperPool* helpers,
                                         SpaceCache* cache,
                                         ServerMetrics* metrics)
    : limits_(std::move(limits)),
      pool_(pool),
      helpers_(helpers),
      cache_(cache),
      metrics_(metrics) {}

std::shared_ptr<TriangulatorService::Job> TriangulatorService::Prepare(
    const v1::TriangulateRequest& request, grpc::ServerContext* context,
    const std::string& rpc, grpc::Status* error) {
  auto job = std::make_shared<Job>();
  job->rpc = rpc;
  job->id = request.id();
  job->arrived = Clock::now();
  job->wire = request.options();
  if (draining_) {
    *error = grpc::Status(grpc::StatusCode::UNAVAILABLE,
                          "server is shutting down; retry on another replica");
    return nullptr;
  }
  job->options.delaunay = limits_.delaunay_backend;
  const Status shape =
      wire::ProblemFromRequest(request, &job->problem, &job->options);
  if (!shape.ok()) {
    *error = wire::ToGrpcStatus(shape);
    return nullptr;
  }
  const size_t n = job->problem.vertices.size();
  if (n > static_cast<size_t>(limits_.max_vertices)) {
    *error = grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                          "polygon has " + std::to_string(n) +
                              " vertices; this server accepts at most " +
                              std::to_string(limits_.max_vertices));
    return nullptr;
  }
  const uint64_t asked = request.options().memory_budget_bytes();
  job->options.memory_budget_bytes =
      asked > 0 ? std::min<int64_t>(static_cast<int64_t>(asked),
                                    limits_.memory_budget_bytes)
                : limits_.memory_budget_bytes;
  job->options.all_space_max_vertices = limits_.all_space_max_vertices;
  const uint32_t budget = request.options().time_budget_ms();
  const int limit_ms = budget > 0
                           ? std::min<int>(budget, limits_.max_compute_ms)
                           : limits_.max_compute_ms;
  job->deadline = job->arrived + std::chrono::milliseconds(limit_ms);
  job->deadline_is_limit = true;
  const auto client_deadline = context->deadline();
  if (client_deadline != std::chrono::system_clock::time_point::max()) {
    const auto left = client_deadline - std::chrono::system_clock::now();
    const auto steady =
        job->arrived + std::chrono::duration_cast<Clock::duration>(left);
    if (steady < job->deadline) {
      job->deadline = steady;
      job->deadline_is_limit = false;
    }
  }
  return job;
}

bool TriangulatorService::Submit(const std::shared_ptr<Job>& job,
                                 bool may_run_here) {
  {
    std::lock_guard<std::mutex> lock(jobs_mu_);
    jobs_.insert(job.get());
  }
  ++inflight_;
  metrics_->inflight().Set(inflight_);
  if (may_run_here && pool_->TryRunHere([this, &job] { Run(*job); })) {
    return true;
  }
  const bool ok = pool_->TrySubmit([this, job] { Run(*job); });
  metrics_->queue_depth().Set(pool_->queued());
  if (!ok) {
    std::lock_guard<std::mutex> lock(jobs_mu_);
    jobs_.erase(job.get());
    --inflight_;
    metrics_->inflight().Set(inflight_);
  }
  return ok;
}

void TriangulatorService::Run(Job& job) {
  job.started = Clock::now();
  metrics_->queue_depth().Set(pool_->queued());
  metrics_->busy_threads().Set(pool_->busy());
  Result result;
  if (job.cancel) {
    result.status =
        MakeStatus(StatusCode::kCancelled, "cancelled while queued");
  } else if (job.started >= job.deadline) {
    result.status = MakeStatus(StatusCode::kDeadlineExceeded,
                               "deadline passed in the queue");
  } else {
    Control control;
    control.cancel = &job.cancel;
    control.deadline = job.deadline;
    if (job.wire.progress_interval_ms() > 0) {
      control.progress = [&job](Stage stage, double fraction) {
        std::lock_guard<std::mutex> lock(job.mu);
        job.progress.set_stage(wire::ToWire(stage));
        job.progress.set_fraction(fraction);
        job.progress.set_elapsed_ms(Ms(Clock::now() - job.arrived));
        job.has_progress = true;
        job.cv.notify_all();
      };
    }
    if (helpers_ != nullptr) {
      control.tetrahedralize = [this, &job](const std::vector<Vec3>& points,
                                            Tetrahedralization* out) {
        const Status s =
            helpers_->Tetrahedralize(points, out, &job.cancel, job.deadline);
        metrics_->helper_starts().Set(static_cast<double>(helpers_->starts()));
        return s;
      };
    }
    if (!job.wire.no_cache()) control.space_cache = cache_;
    try {
      result = dot::Triangulate(job.problem, job.options, control);
      // Counted when the request got as far as a search space.
      if (control.space_cache != nullptr &&
          result.space_used != SpaceUsed::kNone) {
        metrics_->CacheLookup(result.stats.cache_hit,
                              control.space_cache->counters());
      }
    } catch (const std::exception& e) {  // bad_alloc above all
      result = {};
      result.status =
          MakeStatus(StatusCode::kResourceExhausted,
                     std::string("computation failed: ") + e.what());
    }
  }
  std::function<void()> on_done;
  {
    std::lock_guard<std::mutex> lock(job.mu);
    job.result = std::move(result);
    job.finished = Clock::now();
    job.done = true;
    on_done = job.on_done;
  }
  job.cv.notify_all();
  if (on_done) on_done();
}

grpc::Status TriangulatorService::Respond(
    Job& job, grpc::ServerContext* context,
    const std::function<bool(v1::TriangulateResponse&&)>& write) {
  const Result& r = job.result;
  const StatusCode code = r.status.code;
  if (code == StatusCode::kCancelled || context->IsCancelled()) {
    return {grpc::StatusCode::CANCELLED, "cancelled by the client"};
  }
  if (code == StatusCode::kDeadlineExceeded) {
    std::string m = r.status.message;
    if (job.deadline_is_limit) {
      m = "compute time limit exceeded (" + m +
          "); raise options.time_budget_ms up to the server's " +
          std::to_string(limits_.max_compute_ms) + " ms";
    }
    return {grpc::StatusCode::DEADLINE_EXCEEDED, m};
  }
  if (code != StatusCode::kOk && code != StatusCode::kNoTriangulation) {
    return wire::ToGrpcStatus(r.status);
  }
  const size_t first =
      job.wire.omit_input_vertices() ? job.problem.vertices.size() : 0;
  const bool sent = wire::ForEachMeshChunk(
      r, first, limits_.chunk_bytes, [&](v1::MeshChunk&& chunk) {
        v1::TriangulateResponse msg;
        msg.set_id(job.id);
        *msg.mutable_mesh() = std::move(chunk);
        return write(std::move(msg));
      });
  v1::TriangulateResponse msg;
  msg.set_id(job.id);
  v1::Summary* summary = msg.mutable_summary();
  wire::FillSummary(r, summary);
  summary->set_queue_ms(Ms(job.started - job.arrived));
  summary->set_compute_ms(Ms(job.finished - job.started));
  if (!sent || !write(std::move(msg))) {
    return {grpc::StatusCode::CANCELLED, "the client went away"};
  }
  return grpc::Status::OK;
}

void TriangulatorService::Finish(Job& job, const grpc::Status& status,
                                 size_t triangles) {
  {
    std::lock_guard<std::mutex> lock(jobs_mu_);
    if (jobs_.erase(&job) > 0) --inflight_;
  }
  metrics_->inflight().Set(inflight_);
  metrics_->busy_threads().Set(pool_->busy());
  std::string label(wire::GrpcCodeName(status.error_code()));
  if (status.ok() && job.result.status.code == StatusCode::kNoTriangulation) {
    label = "NO_TRIANGULATION";
  }
  const auto now = Clock::now();
  metrics_->RequestDone(job.rpc, label, Ms(now - job.arrived) / 1000);
  const bool ran = job.done;
  spdlog::info(
      "rpc={} id={} n={} weights={} space={} status={} queue_ms={:.1f} "
      "compute_ms={:.1f} triangles={}{}{}",
      job.rpc, job.id, job.problem.vertices.size(),
      WeightsLabel(job.problem.weights),
      ran ? SpaceUsedName(job.result.space_used)
          : SearchSpaceName(job.options.space),
      label, ran ? Ms(job.started - job.arrived) : 0.0,
      ran ? Ms(job.finished - job.started) : 0.0, triangles,
      status.ok() ? "" : " message=\"",
      status.ok() ? "" : status.error_message() + "\"");
}

grpc::Status TriangulatorService::Triangulate(
    grpc::ServerContext* context, const v1::TriangulateRequest* request,
    grpc::ServerWriter<v1::TriangulateResponse>* writer) {
  grpc::Status error;
  std::shared_ptr<Job> job = Prepare(*request, context, "Triangulate", &error);
  if (!job) {
    Job rejected;
    rejected.rpc = "Triangulate";
    rejected.id = request->id();
    rejected.arrived = Clock::now();
    Finish(rejected, error, 0);
    return error;
  }
  // Small requests without progress reports skip the handoff to a worker.
  const bool small = job->wire.progress_interval_ms() == 0 &&
                     job->problem.vertices.size() <=
                         static_cast<size_t>(limits_.inline_max_vertices);
  if (!Submit(job, small)) {
    error = grpc::Status(
        grpc::StatusCode::RESOURCE_EXHAUSTED,
        "server at capacity: " + std::to_string(limits_.queue_size) +
            " requests already queued; retry later");
    Finish(*job, error, 0);
    return error;
  }
  const auto interval =
      std::chrono::milliseconds(job->wire.progress_interval_ms());
  Clock::time_point last_progress{};
  std::unique_lock<std::mutex> lock(job->mu);
  while (!job->done) {
    job->cv.wait_for(lock, std::chrono::milliseconds(10));
    if (context->IsCancelled()) job->cancel = true;
    if (job->has_progress && !job->done && interval.count() > 0 &&
        Clock::now() - last_progress >= interval) {
      last_progress = Clock::now();
      v1::TriangulateResponse msg;
      msg.set_id(job->id);
      *msg.mutable_progress() = job->progress;
      job->has_progress = false;
      lock.unlock();
      if (!writer->Write(msg)) job->cancel = true;
      lock.lock();
    }
  }
  lock.unlock();
  const grpc::Status status = Respond(
      *job, context,
      [writer](v1::TriangulateResponse&& m) { return writer->Write(m); });
  Finish(*job, status, job->result.triangles.size());
  return status;
}

// Per-stream state of TriangulateBatch: finished jobs waiting to be written.
struct TriangulatorService::Batch {
  std::mutex mu;
  std::condition_variable cv;
  std::deque<std::shared_ptr<Job>> finished;
  std::deque<v1::TriangulateResponse> errors;  // items that failed alone
  std::set<std::shared_ptr<Job>> running;
  bool reading_done = false;
};

grpc::Status TriangulatorService::TriangulateBatch(
    grpc::ServerContext* context,
    grpc::ServerReaderWriter<v1::TriangulateResponse, v1::TriangulateRequest>*
        stream) {
  // At most `window` polygons of one stream in flight: memory stays bounded
  // and HTTP/2 flow control pushes back on a fast sender.
  const size_t window = 2 * static_cast<size_t>(limits_.threads) + 2;
  Batch batch;
  auto fail_item = [&](const std::string& id, const grpc::Status& status) {
    Job rejected;
    rejected.rpc = "TriangulateBatch";
    rejected.id = id;
    rejected.arrived = Clock::now();
    Finish(rejected, status, 0);
    v1::TriangulateResponse msg;
    msg.set_id(id);
    msg.mutable_error()->set_code(status.error_code());
    msg.mutable_error()->set_message(status.error_message());
    std::lock_guard<std::mutex> lock(batch.mu);
    batch.errors.push_back(std::move(msg));
    batch.cv.notify_all();
  };
  std::thread reader([&] {
    v1::TriangulateRequest request;
    while (stream->Read(&request)) {
      {
        std::unique_lock<std::mutex> lock(batch.mu);
        batch.cv.wait(lock, [&] {
          return batch.running.size() < window || context->IsCancelled();
        });
        if (context->IsCancelled()) break;
      }
      grpc::Status error;
      std::shared_ptr<Job> job =
          Prepare(request, context, "TriangulateBatch", &error);
      if (!job) {
        fail_item(request.id(), error);
        continue;
      }
      job->on_done = [&batch, raw = job.get()] {
        std::lock_guard<std::mutex> lock(batch.mu);
        for (const auto& j : batch.running) {
          if (j.get() == raw) {
            batch.finished.push_back(j);
            break;
          }
        }
        batch.cv.notify_all();
      };
      {
        std::lock_guard<std::mutex> lock(batch.mu);
        batch.running.insert(job);
      }
      if (!Submit(job, false)) {
        {
          std::lock_guard<std::mutex> lock(batch.mu);
          batch.running.erase(job);
        }
        Finish(*job, {}, 0);
        fail_item(request.id(),
                  {grpc::StatusCode::RESOURCE_EXHAUSTED,
                   "server at capacity: " + std::to_string(limits_.queue_size) +
                       " requests already queued; retry later"});
      }
    }
    std::lock_guard<std::mutex> lock(batch.mu);
    batch.reading_done = true;
    batch.cv.notify_all();
  });

  bool client_gone = false;
  for (;;) {
    std::shared_ptr<Job> job;
    std::optional<v1::TriangulateResponse> error;
    {
      std::unique_lock<std::mutex> lock(batch.mu);
      batch.cv.wait_for(lock, std::chrono::milliseconds(10), [&] {
        return !batch.finished.empty() || !batch.errors.empty() ||
               (batch.reading_done && batch.running.empty());
      });
      if (context->IsCancelled() && !client_gone) {
        client_gone = true;
        for (const auto& j : batch.running) j->cancel = true;
      }
      if (!batch.errors.empty()) {
        error = std::move(batch.errors.front());
        batch.errors.pop_front();
      } else if (!batch.finished.empty()) {
        job = batch.finished.front();
        batch.finished.pop_front();
        batch.running.erase(job);
        batch.cv.notify_all();  // a window slot is free
      } else if (batch.reading_done && batch.running.empty()) {
        break;
      } else {
        continue;
      }
    }
    if (error) {
      if (!client_gone && !stream->Write(*error)) client_gone = true;
      continue;
    }
    grpc::Status status = grpc::Status::OK;
    if (!client_gone) {
      status = Respond(*job, context, [&](v1::TriangulateResponse&& m) {
        return stream->Write(m);
      });
      if (status.error_code() == grpc::StatusCode::CANCELLED &&
          context->IsCancelled()) {
        client_gone = true;
      } else if (!status.ok()) {
        v1::TriangulateResponse msg;
        msg.set_id(job->id);
        msg.mutable_error()->set_code(status.error_code());
        msg.mutable_error()->set_message(status.error_message());
        if (!stream->Write(msg)) client_gone = true;
      }
    } else {
      status = grpc::Status(grpc::StatusCode::CANCELLED, "client went away");
    }
    Finish(*job, status, job->result.triangles.size());
  }
  reader.join();
  if (client_gone)
    return {grpc::StatusCode::CANCELLED, "cancelled by the client"};
  return grpc::Status::OK;
}

void TriangulatorService::CancelAll() {
  std::lock_guard<std::mutex> lock(jobs_mu_);
  for (Job* job : jobs_) job->cancel = true;
}

grpc::Status TriangulatorService::GetServerInfo(grpc::ServerContext*,
                                                const v1::GetServerInfoRequest*,
                                                v1::ServerInfo* info) {
  info->set_version(DOT_VERSION);
  info->set_build(DOT_BUILD_INFO);
  info->add_backends(
      std::string("cgal-5.5 Delaunay 3D") +
      (limits_.delaunay_backend == DelaunayBackend::kCgal ? " (default)" : ""));
  info->add_backends(std::string(helpers_ ? "tetgen-1.5 (helper processes)"
                                          : "tetgen-1.5 (in-process, "
                                            "serialized)") +
                     (limits_.delaunay_backend == DelaunayBackend::kTetgen
                          ? " (default)"
                          : ""));
  info->add_backends("cgal-5.5 constrained Delaunay 2D (planar polygons)");
  info->add_backends("all-triangles GK1/GK2");
  v1::Limits* l = info->mutable_limits();
  l->set_max_vertices(limits_.max_vertices);
  l->set_max_compute_ms(limits_.max_compute_ms);
  l->set_memory_budget_bytes(limits_.memory_budget_bytes);
  l->set_compute_threads(limits_.threads);
  l->set_cache_bytes(cache_ ? static_cast<uint64_t>(cache_->max_bytes()) : 0);
  l->set_queue_size(limits_.queue_size);
  l->set_all_space_max_vertices(limits_.all_space_max_vertices);
  l->set_max_message_bytes(limits_.max_message_bytes);
  info->set_license("AGPL-3.0-or-later");
  info->set_source_url(limits_.source_url);
  info->set_source_note(
      "This service is free software under the GNU AGPL v3 or later (it "
      "links TetGen, AGPL-3.0+). Its complete corresponding source is "
      "available to every user: call GetSource (dotctl source -o "
      "dot-source.tar.gz)" +
      std::string(limits_.source_url.empty()
                      ? "."
                      : " or download it from " + limits_.source_url + "."));
  return grpc::Status::OK;
}

grpc::Status TriangulatorService::GetSource(
    grpc::ServerContext* context, const v1::GetSourceRequest*,
    grpc::ServerWriter<v1::SourceChunk>* writer) {
  std::ifstream in(limits_.source_archive, std::ios::binary);
  if (limits_.source_archive.empty() || !in) {
    return {grpc::StatusCode::UNIMPLEMENTED,
            "this server has no source archive (--source-archive '" +
                limits_.source_archive + "'); " +
                (limits_.source_url.empty()
                     ? "ask its operator for the source"
                     : "the source is at " + limits_.source_url)};
  }
  std::vector<char> buf(256 * 1024);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize got = in.gcount();
    if (got <= 0) break;
    v1::SourceChunk chunk;
    chunk.set_data(buf.data(), static_cast<size_t>(got));
    if (context->IsCancelled() || !writer->Write(chunk)) {
      return {grpc::StatusCode::CANCELLED, "cancelled by the client"};
    }
  }
  return grpc::Status::OK;
}

}  // namespace dot::server
