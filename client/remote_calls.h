// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl's calls to a dot-server, through the dotctl-remote module
// (remote/): dotctl loads it with dlopen at its first remote command, so a
// process that never calls a server (--local, generate, view, --version)
// never loads gRPC and its 45 shared libraries, which cost ~20 ms of
// every start. A channel is opaque here: the module makes, uses and frees
// it (a gRPC channel and its stubs).
#ifndef DOT_CLIENT_REMOTE_CALLS_H_
#define DOT_CLIENT_REMOTE_CALLS_H_

// gRPC's Status: a value type, used here through its inline members only
// (not Status::OK, which is libgrpc++'s).
#include <grpcpp/support/status.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "fill_call.h"
#include "grpc/health/v1/health.pb.h"
#include "remote_call.h"
#include "request_flags.h"
#include "surface_call.h"

namespace dot::client {

struct RemoteChannel;  // the module's
using Channel = std::shared_ptr<RemoteChannel>;

// The module's entry points. Every function is safe to call from several
// threads at once on one channel.
struct RemoteCalls {
  // A channel to flags.server (MakeChannel) with its stubs, or null with
  // `*error`.
  Channel (*make_channel)(const ConnectionFlags& flags, std::string* error);
  // One Triangulate call (TriangulateRemote).
  CallOutcome (*triangulate)(
      const Channel& channel, const v1::TriangulateRequest& request,
      const std::vector<Vec3>& input, double timeout_s,
      const std::function<void(const v1::Progress&)>& on_progress);
  // One FillHoles call (FillRemote).
  FillOutcome (*fill)(const Channel& channel, const std::string& id,
                      const v1::FillOptions& options, const PolygonSoup& mesh,
                      double timeout_s, const FillProgressFn& on_progress);
  // One SurfaceNetwork call (SurfaceRemote).
  SurfaceOutcome (*surface)(const Channel& channel, const std::string& id,
                            const v1::SurfaceOptions& options,
                            const CurveNetwork& network, double timeout_s,
                            const SurfaceProgressFn& on_progress);
  // One TriangulateBatch stream: a writer thread sends what `next` gives
  // (valid until its next call; null ends the writes; it may block), and
  // every message read goes to `on_answer` on the calling thread. Once the
  // last is read, `reads_done` (if set) must release a `next` that blocks:
  // the writer is then waited for. Returns the stream's status.
  grpc::Status (*batch)(
      const Channel& channel, std::chrono::system_clock::time_point deadline,
      const std::function<const v1::TriangulateRequest*()>& next,
      const std::function<void(const v1::TriangulateResponse&)>& on_answer,
      const std::function<void()>& reads_done);
  // grpc.health.v1.Health/Check of `service`.
  grpc::Status (*check_health)(const Channel& channel,
                               const std::string& service, double timeout_s,
                               grpc::health::v1::HealthCheckResponse* response);
  // GetServerInfo.
  grpc::Status (*server_info)(const Channel& channel, double timeout_s,
                              v1::ServerInfo* info);
  // GetSource: each chunk of the tarball to `on_chunk`, in order.
  grpc::Status (*source)(
      const Channel& channel, double timeout_s,
      const std::function<void(const std::string&)>& on_chunk);
};

// The module's calls, loaded on the first call (thread-safe, once per
// process), or null with `*error` naming the file and why it did not load.
// The module is looked for beside dotctl (a build tree), then in
// <libdir>/dot/ relative to dotctl's <bindir> (an install).
const RemoteCalls* LoadRemoteCalls(std::string* error);

// The module's file name, and the C symbol it exports: a function taking
// the build key it must match (DOT_REMOTE_ABI: the version and a hash of
// the headers whose types cross the table) and the table's size, and
// returning its RemoteCalls (null when either differs).
inline constexpr const char* kRemoteModuleFile = "dotctl-remote.so";
inline constexpr const char* kRemoteModuleEntry = "dot_client_remote_calls";

}  // namespace dot::client

#endif  // DOT_CLIENT_REMOTE_CALLS_H_
