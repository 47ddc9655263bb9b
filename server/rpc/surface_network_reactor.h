// SPDX-License-Identifier: AGPL-3.0-or-later
// SurfaceNetwork, the transport: the network streams in (first message: id
// and options; each message accepted by SurfaceUpload), the use case
// (SurfaceNetworkCall) runs on the compute pool as one job, and progress
// per patch, the surface and the report stream back (UploadReactor).
#ifndef DOT_SERVER_RPC_SURFACE_NETWORK_REACTOR_H_
#define DOT_SERVER_RPC_SURFACE_NETWORK_REACTOR_H_

#include "dot/v1/triangulation.pb.h"
#include "rpc/surface_network_call.h"
#include "rpc/upload_reactor.h"

namespace dot::server {

struct SurfaceNetworkUse {
  using Request = v1::SurfaceNetworkRequest;
  using Response = v1::SurfaceNetworkResponse;
  using Input = CurveNetwork;
  using Upload = SurfaceUpload;
  using Call = SurfaceNetworkCall;
  static constexpr char kMethod[] = "SurfaceNetwork";
  static constexpr char kInput[] = "network";
  using Progress = std::function<void(
      bool force, const std::function<void(Response*)>& fill)>;
  // The surface, with progress after the cycles and each patch.
  static Status Run(Call& call, Input network, Job& job, const Control& control,
                    const Progress& progress);
};

using SurfaceNetworkReactor = UploadReactor<SurfaceNetworkUse>;

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_SURFACE_NETWORK_REACTOR_H_
