// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/surface_network_call.h"

#include "rpc/fill_upload.h"

namespace dot::server {

SurfaceUpload::SurfaceUpload(JobRunner* runner)
    : runner_(runner),
      reader_(static_cast<size_t>(runner->options().fill_max_vertices),
              static_cast<size_t>(runner->options().fill_max_faces)) {}

SurfaceUpload::~SurfaceUpload() { runner_->ReleaseFillMemory(charged_); }

grpc::Status SurfaceUpload::Add(const v1::SurfaceNetworkRequest& m, Job& job) {
  grpc::Status go_on = UploadMayGoOn(job, "network");
  if (!go_on.ok()) return go_on;
  const Status s = reader_.Add(m);
  if (!s.ok()) return wire::ToGrpcStatus(s);
  const int64_t bytes =
      FillMemoryBytes(static_cast<int64_t>(reader_.vertices()),
                      static_cast<int64_t>(reader_.polylines()));
  return ChargeUpload(runner_, bytes, "SurfaceNetwork", "network", &charged_);
}

Status SurfaceNetworkCall::Configure(const v1::SurfaceOptions& wire,
                                     const ServiceOptions& server,
                                     int threads) {
  const Status s = wire::SurfaceOptionsFromWire(wire, &options_);
  if (!s.ok()) return s;
  options_.triangulate = server.solve;
  options_.triangulate.space = SearchSpace::kDelaunay;
  options_.triangulate.memory_budget_bytes =
      RequestMemoryBudget(server, wire.memory_budget_bytes());
  options_.threads = threads;
  return CheckSurfaceOptions(options_);
}

Status SurfaceNetworkCall::Run(CurveNetwork network, const Control& control,
                               const SurfaceProgressFn& on_progress,
                               std::string* log) {
  *log = "received_vertices=" + std::to_string(network.vertices.size()) +
         " received_polylines=" + std::to_string(network.polylines.size());
  input_vertices_ = network.vertices.size();
  result_ = SurfaceNetwork(network, options_, control, on_progress);
  const SurfaceReport& r = result_.report;
  if (result_.status.ok()) {
    *log += " curves=" + std::to_string(r.curves) +
            " patches=" + std::to_string(r.patches.size()) +
            " surfaced=" + std::to_string(r.surfaced) +
            " faces=" + std::to_string(result_.mesh.triangles.size());
  }
  return result_.status;
}

void SurfaceNetworkCall::Next(const std::string& id, size_t chunk_bytes,
                              v1::SurfaceNetworkResponse* message) {
  if (!chunks_) {
    chunks_.emplace(result_.mesh.vertices, result_.mesh.triangles, 0,
                    chunk_bytes);
  }
  message->Clear();
  message->set_id(id);
  if (chunks_->Next(message->mutable_mesh())) return;
  wire::SurfaceReportToWire(result_.report, input_vertices_, result_.mesh,
                            message->mutable_report());
  done_ = true;
}

}  // namespace dot::server
