// SPDX-License-Identifier: AGPL-3.0-or-later
// The SurfaceNetwork use case, with no stream in it: the network as it
// arrives (SurfaceUpload: under the server's limits and memory for
// uploads), the request's options checked once and put under the server's
// limits, the surface itself (dot::SurfaceNetwork, the function dotctl
// --local runs too), and the answer as response messages made one at a
// time: the mesh in chunks, then the report.
#ifndef DOT_SERVER_RPC_SURFACE_NETWORK_CALL_H_
#define DOT_SERVER_RPC_SURFACE_NETWORK_CALL_H_

#include <grpcpp/grpcpp.h>

#include <optional>
#include <string>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "rpc/job.h"
#include "rpc/service_options.h"
#include "wire/surface_wire.h"
#include "wire/wire.h"

namespace dot::server {

// Networks are bounded as FillHoles meshes are: at most fill_max_vertices
// points and fill_max_faces polylines, charged FillMemoryBytes(points,
// polylines + their points) of the server's memory for uploads while held.
class SurfaceUpload {
 public:
  explicit SurfaceUpload(JobRunner* runner);
  ~SurfaceUpload();  // gives the charge back
  SurfaceUpload(const SurfaceUpload&) = delete;
  SurfaceUpload& operator=(const SurfaceUpload&) = delete;

  grpc::Status Add(const v1::SurfaceNetworkRequest& message, Job& job);
  Status Finish(CurveNetwork* network) { return reader_.Finish(network); }
  size_t messages() const { return reader_.messages(); }

 private:
  JobRunner* const runner_;
  wire::SurfaceRequestReader reader_;
  int64_t charged_ = 0;
};

class SurfaceNetworkCall {
 public:
  // The first message's options: not OK names what is wrong with them.
  // Each patch runs with the server's solve options and the request's
  // memory budget (clamped to the server's), `threads` patches at once.
  Status Configure(const v1::SurfaceOptions& wire, const ServiceOptions& server,
                   int threads);
  // The surface, on a compute thread. `log` receives the call's log detail.
  Status Run(CurveNetwork network, const Control& control,
             const SurfaceProgressFn& on_progress, std::string* log);
  bool partial() const { return false; }  // a stop keeps nothing
  // After a Run that succeeded: the next message of the answer, tagged
  // `id`; the last one (done() after it) is the report.
  void Next(const std::string& id, size_t chunk_bytes,
            v1::SurfaceNetworkResponse* message);
  bool done() const { return done_; }

 private:
  SurfaceOptions options_;
  SurfaceResult result_;
  size_t input_vertices_ = 0;
  std::optional<wire::MeshChunker> chunks_;
  bool done_ = false;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_SURFACE_NETWORK_CALL_H_
