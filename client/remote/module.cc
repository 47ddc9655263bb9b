// SPDX-License-Identifier: AGPL-3.0-or-later
// The dotctl-remote module's entry point, its one exported symbol (the
// linker script exports.map hides the rest): grpc_calls.h behind the
// RemoteCalls table that dotctl loads (remote_calls.h). Everything else the
// module uses (the wire mapping, the core, the protobuf messages) is
// dotctl's own, exported by the executable: one copy of each per process.
#include <cstring>

#include "remote/grpc_calls.h"
#include "remote_calls.h"

namespace dot::client {

// A channel and its stubs, made once per connection (a stub registers its
// methods on the channel).
struct RemoteChannel {
  std::shared_ptr<grpc::Channel> channel;
  std::unique_ptr<v1::Triangulator::Stub> triangulator;
  std::unique_ptr<grpc::health::v1::Health::Stub> health;
};

namespace {

Channel Connect(const ConnectionFlags& flags, std::string* error) {
  auto c = std::make_shared<RemoteChannel>();
  c->channel = MakeChannel(flags, error);
  if (!c->channel) return nullptr;
  c->triangulator = v1::Triangulator::NewStub(c->channel);
  c->health = grpc::health::v1::Health::NewStub(c->channel);
  return c;
}

CallOutcome Triangulate(
    const Channel& channel, const v1::TriangulateRequest& request,
    const std::vector<Vec3>& input, double timeout_s,
    const std::function<void(const v1::Progress&)>& on_progress) {
  return TriangulateRemote(*channel->triangulator, request, input, timeout_s,
                           on_progress);
}

FillOutcome Fill(const Channel& channel, const std::string& id,
                 const v1::FillOptions& options, const PolygonSoup& mesh,
                 double timeout_s, const FillProgressFn& on_progress) {
  return FillRemote(*channel->triangulator, id, options, mesh, timeout_s,
                    on_progress);
}

SurfaceOutcome Surface(const Channel& channel, const std::string& id,
                       const v1::SurfaceOptions& options,
                       const CurveNetwork& network, double timeout_s,
                       const SurfaceProgressFn& on_progress) {
  return SurfaceRemote(*channel->triangulator, id, options, network, timeout_s,
                       on_progress);
}

grpc::Status Batch(
    const Channel& channel, std::chrono::system_clock::time_point deadline,
    const std::function<const v1::TriangulateRequest*()>& next,
    const std::function<void(const v1::TriangulateResponse&)>& on_answer,
    const std::function<void()>& reads_done) {
  return TriangulateBatchRemote(*channel->triangulator, deadline, next,
                                on_answer, reads_done);
}

grpc::Status CheckHealth(const Channel& channel, const std::string& service,
                         double timeout_s,
                         grpc::health::v1::HealthCheckResponse* response) {
  return CheckHealthRemote(*channel->health, service, timeout_s, response);
}

grpc::Status ServerInfo(const Channel& channel, double timeout_s,
                        v1::ServerInfo* info) {
  return ServerInfoRemote(*channel->triangulator, timeout_s, info);
}

grpc::Status Source(const Channel& channel, double timeout_s,
                    const std::function<void(const std::string&)>& on_chunk) {
  return SourceRemote(*channel->triangulator, timeout_s, on_chunk);
}

constexpr RemoteCalls kCalls{Connect, Triangulate, Fill,       Surface,
                             Batch,   CheckHealth, ServerInfo, Source};

}  // namespace
}  // namespace dot::client

// Null unless dotctl is this module's own build (its key, its table).
extern "C" __attribute__((visibility("default")))
const dot::client::RemoteCalls*
dot_client_remote_calls(const char* version, size_t table_size) {
  if (std::strcmp(version, DOT_REMOTE_ABI) != 0 ||
      table_size != sizeof(dot::client::RemoteCalls)) {
    return nullptr;
  }
  return &dot::client::kCalls;
}
