// SPDX-License-Identifier: AGPL-3.0-or-later
// The gRPC half of dotctl: every call it makes to a dot-server. Built into
// the dotctl-remote module (module.cc), which dotctl loads at its first
// remote command (remote_calls.h); the service tests link it directly.
#ifndef DOT_CLIENT_REMOTE_GRPC_CALLS_H_
#define DOT_CLIENT_REMOTE_GRPC_CALLS_H_

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dot/v1/triangulation.grpc.pb.h"
#include "fill_call.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "remote_call.h"
#include "request_flags.h"
#include "surface_call.h"

namespace dot::client {

// A channel with the retry policy (UNAVAILABLE is retried on another
// connection) and round-robin balancing over every resolved address; null
// with `*error` when a TLS file cannot be read.
std::shared_ptr<grpc::Channel> MakeChannel(const ConnectionFlags& flags,
                                           std::string* error);

// One Triangulate call: the stream read whole, the mesh reassembled.
CallOutcome TriangulateRemote(
    v1::Triangulator::Stub& stub, const v1::TriangulateRequest& request,
    const std::vector<Vec3>& input, double timeout_s,
    const std::function<void(const v1::Progress&)>& on_progress = nullptr);

// FillLocal's call over a server: the mesh's attribute channels are sent,
// and the answer is shaped as FillLocal's.
FillOutcome FillRemote(v1::Triangulator::Stub& stub, const std::string& id,
                       const v1::FillOptions& options, const PolygonSoup& mesh,
                       double timeout_s,
                       const FillProgressFn& on_progress = nullptr);

// SurfaceLocal's call over a server.
SurfaceOutcome SurfaceRemote(v1::Triangulator::Stub& stub,
                             const std::string& id,
                             const v1::SurfaceOptions& options,
                             const CurveNetwork& network, double timeout_s,
                             const SurfaceProgressFn& on_progress = nullptr);

// RemoteCalls::batch, check_health, server_info and source.
grpc::Status TriangulateBatchRemote(
    v1::Triangulator::Stub& stub,
    std::chrono::system_clock::time_point deadline,
    const std::function<const v1::TriangulateRequest*()>& next,
    const std::function<void(const v1::TriangulateResponse&)>& on_answer,
    const std::function<void()>& reads_done);
grpc::Status CheckHealthRemote(grpc::health::v1::Health::Stub& stub,
                               const std::string& service, double timeout_s,
                               grpc::health::v1::HealthCheckResponse* response);
grpc::Status ServerInfoRemote(v1::Triangulator::Stub& stub, double timeout_s,
                              v1::ServerInfo* info);
grpc::Status SourceRemote(
    v1::Triangulator::Stub& stub, double timeout_s,
    const std::function<void(const std::string&)>& on_chunk);

}  // namespace dot::client

#endif  // DOT_CLIENT_REMOTE_GRPC_CALLS_H_
