// SPDX-License-Identifier: AGPL-3.0-or-later
// One Triangulate call, remote (streamed, reassembled) or local (the core
// in-process, through the same wire mapping), with one outcome type.
#ifndef DOT_CLIENT_REMOTE_CALL_H_
#define DOT_CLIENT_REMOTE_CALL_H_

#include <grpcpp/grpcpp.h>

#include <functional>
#include <string>

#include "dot/dot.h"
#include "dot/v1/triangulation.grpc.pb.h"

namespace dot::client {

struct CallOutcome {
  grpc::Status status;  // of the RPC (or of the local run)
  v1::Summary summary;  // valid when status is OK
  MeshData mesh;        // the mesh, when summary.status is OK
  double latency_ms = 0;
};

CallOutcome TriangulateRemote(
    v1::Triangulator::Stub& stub, const v1::TriangulateRequest& request,
    const std::vector<Vec3>& input, double timeout_s,
    const std::function<void(const v1::Progress&)>& on_progress = nullptr);

CallOutcome TriangulateLocal(const v1::TriangulateRequest& request);

// "ok: 98 triangles, DOT2 over delaunay3d, cost ..." for people.
std::string DescribeOutcome(const CallOutcome& outcome);
// One JSON object for scripts.
std::string OutcomeJson(const std::string& name, const CallOutcome& outcome,
                        const std::string& output_path);
std::string JsonQuote(const std::string& s);

}  // namespace dot::client

#endif  // DOT_CLIENT_REMOTE_CALL_H_
