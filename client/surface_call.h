// SPDX-License-Identifier: AGPL-3.0-or-later
// One SurfaceNetwork call, over the server or in this process, with the
// same outcome either way: the status, the report and the surface.
#ifndef DOT_CLIENT_SURFACE_CALL_H_
#define DOT_CLIENT_SURFACE_CALL_H_

#include <grpcpp/support/status.h>

#include <functional>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace dot::client {

struct SurfaceOutcome {
  grpc::Status status;       // of the RPC (or of the local run)
  v1::SurfaceReport report;  // valid when status is OK
  MeshData mesh;             // the surface: the network's vertices first
  double latency_ms = 0;
};

using SurfaceProgressFn = std::function<void(const v1::SurfaceProgress&)>;

// In this process: dot::SurfaceNetwork with the options a server applies
// (wire::SurfaceOptionsFromWire), the request's time budget as deadline.
SurfaceOutcome SurfaceLocal(const v1::SurfaceOptions& options,
                            const CurveNetwork& network,
                            const SurfaceProgressFn& on_progress = nullptr);

// What a user should know besides the counts, one line each: dangling
// curves, patches left open, non-manifold curves, the report's notes.
std::vector<std::string> SurfaceNotes(const v1::SurfaceReport& report);

// The JSON object dotctl prints for a surface (--json): the shared
// envelope, then "report".
std::string SurfaceOutcomeJson(const std::string& input,
                               const SurfaceOutcome& o,
                               const std::string& output_path,
                               const std::string& outcome, int exit_code,
                               const std::string& error, bool called);

}  // namespace dot::client

#endif  // DOT_CLIENT_SURFACE_CALL_H_
