// SPDX-License-Identifier: AGPL-3.0-or-later
// The dotctl-remote module's one exported symbol: grpc_calls.h behind the
// RemoteCalls table that dotctl loads (remote_calls.h). Everything else the
// module uses (the wire mapping, the core, the protobuf messages) is
// dotctl's own, exported by the executable: one copy of each per process.
#include <cstring>

#include "remote/grpc_calls.h"
#include "remote_calls.h"

namespace dot::client {
namespace {

CallOutcome Triangulate(
    const Channel& channel, const v1::TriangulateRequest& request,
    const std::vector<Vec3>& input, double timeout_s,
    const std::function<void(const v1::Progress&)>& on_progress) {
  auto stub = v1::Triangulator::NewStub(channel);
  return TriangulateRemote(*stub, request, input, timeout_s, on_progress);
}

FillOutcome Fill(const Channel& channel, const std::string& id,
                 const v1::FillOptions& options, const PolygonSoup& mesh,
                 double timeout_s, const FillProgressFn& on_progress) {
  auto stub = v1::Triangulator::NewStub(channel);
  return FillRemote(*stub, id, options, mesh, timeout_s, on_progress);
}

SurfaceOutcome Surface(const Channel& channel, const std::string& id,
                       const v1::SurfaceOptions& options,
                       const CurveNetwork& network, double timeout_s,
                       const SurfaceProgressFn& on_progress) {
  auto stub = v1::Triangulator::NewStub(channel);
  return SurfaceRemote(*stub, id, options, network, timeout_s, on_progress);
}

grpc::Status Batch(
    const Channel& channel, std::chrono::system_clock::time_point deadline,
    const std::function<const v1::TriangulateRequest*()>& next,
    const std::function<void(const v1::TriangulateResponse&)>& on_answer,
    const std::function<void()>& reads_done) {
  auto stub = v1::Triangulator::NewStub(channel);
  return TriangulateBatchRemote(*stub, deadline, next, on_answer, reads_done);
}

grpc::Status CheckHealth(const Channel& channel, const std::string& service,
                         double timeout_s,
                         grpc::health::v1::HealthCheckResponse* response) {
  auto stub = grpc::health::v1::Health::NewStub(channel);
  return CheckHealthRemote(*stub, service, timeout_s, response);
}

grpc::Status ServerInfo(const Channel& channel, double timeout_s,
                        v1::ServerInfo* info) {
  auto stub = v1::Triangulator::NewStub(channel);
  return ServerInfoRemote(*stub, timeout_s, info);
}

grpc::Status Source(const Channel& channel, double timeout_s,
                    const std::function<void(const std::string&)>& on_chunk) {
  auto stub = v1::Triangulator::NewStub(channel);
  return SourceRemote(*stub, timeout_s, on_chunk);
}

constexpr RemoteCalls kCalls{MakeChannel, Triangulate, Fill,       Surface,
                             Batch,       CheckHealth, ServerInfo, Source};

}  // namespace
}  // namespace dot::client

// Null unless dotctl is this module's own build (its version, its table).
extern "C" __attribute__((visibility("default")))
const dot::client::RemoteCalls*
dot_client_remote_calls(const char* version, size_t table_size) {
  if (std::strcmp(version, DOT_VERSION) != 0 ||
      table_size != sizeof(dot::client::RemoteCalls)) {
    return nullptr;
  }
  return &dot::client::kCalls;
}
