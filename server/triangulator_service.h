// SPDX-License-Identifier: AGPL-3.0-or-later
// dot.v1.Triangulator on gRPC's synchronous API. Each request becomes a Job
// that runs on the bounded ComputePool; the RPC thread waits for it,
// streams progress, turns client cancellation into the core's cancel flag,
// and finally streams the mesh in chunks and a summary.
#ifndef DOT_SERVER_TRIANGULATOR_SERVICE_H_
#define DOT_SERVER_TRIANGULATOR_SERVICE_H_

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include "compute_pool.h"
#include "delaunay_helpers.h"
#include "dot/space_cache.h"
#include "dot/triangulate.h"
#include "dot/v1/triangulation.grpc.pb.h"
#include "server_metrics.h"

namespace dot::server {

struct ServiceLimits {
  int max_vertices = 1000000;
  int max_compute_ms = 60000;
  int64_t memory_budget_bytes = int64_t{2} << 30;
  int all_space_max_vertices = 40;
  size_t chunk_bytes = 1 << 20;
  int max_message_bytes = 16 << 20;
  int threads = 1;
  int queue_size = 64;
  DelaunayBackend delaunay_backend = DelaunayBackend::kCgal;
  // Triangulate calls up to this size run on the RPC's own thread when a
  // compute slot is free (no handoff); larger ones and batches are queued.
  int inline_max_vertices = 500;
  std::string source_archive;
  std::string source_url;
};

class TriangulatorService final : public v1::Triangulator::Service {
 public:
  // `helpers` may be null: TetGen then runs in-process, serialized.
  // `cache` may be null: no search-space cache.
  TriangulatorService(ServiceLimits limits, ComputePool* pool,
                      DelaunayHelperPool* helpers, SpaceCache* cache,
                      ServerMetrics* metrics);

  grpc::Status Triangulate(
      grpc::ServerContext* context, const v1::TriangulateRequest* request,
      grpc::ServerWriter<v1::TriangulateResponse>* writer) override;
  grpc::Status TriangulateBatch(
      grpc::ServerContext* context,
      grpc::ServerReaderWriter<v1::TriangulateResponse, v1::TriangulateRequest>*
          stream) override;
  grpc::Status GetServerInfo(grpc::ServerContext* context,
                             const v1::GetServerInfoRequest* request,
                             v1::ServerInfo* info) override;
  grpc::Status GetSource(grpc::ServerContext* context,
                         const v1::GetSourceRequest* request,
                         grpc::ServerWriter<v1::SourceChunk>* writer) override;

  // New requests are refused with UNAVAILABLE from now on.
  void StartDraining() { draining_ = true; }
  int inflight() const { return inflight_; }
  void CancelAll();  // sets the cancel flag of every running job

 private:
  struct Job;
  struct Batch;
  std::shared_ptr<Job> Prepare(const v1::TriangulateRequest& request,
                               grpc::ServerContext* context,
                               const std::string& rpc, grpc::Status* error);
  // Queues the job, or with `may_run_here` runs it on this thread when a
  // compute slot is free. False when the queue is full.
  bool Submit(const std::shared_ptr<Job>& job, bool may_run_here);
  void Run(Job& job);
  // Streams chunks and summary of a finished job, or returns its error.
  grpc::Status Respond(
      Job& job, grpc::ServerContext* context,
      const std::function<bool(v1::TriangulateResponse&&)>& write);
  void Finish(Job& job, const grpc::Status& status, size_t triangles);

  const ServiceLimits limits_;
  ComputePool* pool_;
  DelaunayHelperPool* helpers_;
  SpaceCache* cache_;
  ServerMetrics* metrics_;
  std::atomic<bool> draining_{false};
  std::atomic<int> inflight_{0};
  std::mutex jobs_mu_;
  std::set<Job*> jobs_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_TRIANGULATOR_SERVICE_H_
