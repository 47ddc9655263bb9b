// SPDX-License-Identifier: AGPL-3.0-or-later
// One Triangulate call's outcome, remote (remote_calls.h: streamed,
// reassembled) or local (the core in-process, through the same wire
// mapping), and what dotctl reports of it.
#ifndef DOT_CLIENT_REMOTE_CALL_H_
#define DOT_CLIENT_REMOTE_CALL_H_

#include <grpcpp/support/status.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dot/delaunay_helpers.h"
#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace dot::client {

struct CallOutcome {
  grpc::Status status;  // of the RPC (or of the local run)
  v1::Summary summary;  // valid when status is OK
  MeshData mesh;        // the mesh, when summary.status is OK
  double latency_ms = 0;
};

// The core in this process, with the request's time and memory budgets.
// With `helpers`, TetGen runs in them (as in dot-server): TetGen 1.5 aborts
// on some degenerate inputs, which must fail the call, not dotctl.
CallOutcome TriangulateLocal(const v1::TriangulateRequest& request,
                             DelaunayHelperPool* helpers);
// `count` TetGen helper processes, each dotctl itself in its helper mode
// (kDelaunayHelperArgument); null in a build without TetGen. Made only
// when TetGen is asked for: the pool ignores SIGPIPE process-wide, so
// that `dotctl ... -o - | head` would then report EPIPE instead of ending
// quietly.
std::unique_ptr<DelaunayHelperPool> LocalDelaunayHelpers(int count);
// dotctl's first argument that makes it a Delaunay helper process.
inline constexpr const char* kDelaunayHelperArgument = "--delaunay-helper";

// "ok: 98 triangles, DOT2 over delaunay3d, cost ..." for people.
std::string DescribeOutcome(const CallOutcome& outcome);
// "OK in 12.3 ms (compute 8.1 ms)" for -v.
std::string DescribeTiming(const CallOutcome& outcome);

// The outcomes of one input of triangulate and batch (JSON "outcome").
inline constexpr const char* kOutcomeOk = "ok";
inline constexpr const char* kOutcomeNoTriangulation = "no_triangulation";
inline constexpr const char* kOutcomeInputError = "input_error";
inline constexpr const char* kOutcomeOutputError = "output_error";
inline constexpr const char* kOutcomeCallFailed = "call_failed";
inline constexpr const char* kOutcomeWriteFailed = "write_failed";
// fill-holes: some selected hole left open (exit 4; the report says why).
inline constexpr const char* kOutcomeHolesOpen = "holes_open";
// fill-holes: stopped early (time limit, drain); what it filled is written.
inline constexpr const char* kOutcomePartial = "partial";

// What dotctl reports for one input, whatever became of it.
struct InputReport {
  std::string input;
  std::string outcome = kOutcomeOk;
  int exit_code = 0;
  std::string error;                  // why, for every outcome but ok
  const CallOutcome* call = nullptr;  // when a call was made
  std::string output;                 // the mesh written: a path, "-"
  std::vector<std::string> notes;     // what reading the input changed
  // Triangles of the result facing against the given normals (and those
  // whose facing the normals decide); -1: not checked (no normals, no mesh).
  int faces_against_normals = -1;
  int faces_checked = 0;
  // Most triangles face against the normals: the loop probably runs the
  // other way round (or the normals point to the other side).
  bool OrientationContradictsNormals() const {
    return faces_against_normals > 0 &&
           2 * faces_against_normals > faces_checked;
  }
};
// Counts the triangles of `mesh` (input vertices first, oriented so that
// the loop runs counter-clockwise around their normal) whose normal points
// against the sum of the given normals at their corners.
void CheckOrientation(const MeshData& mesh, const std::vector<Vec3>& normals,
                      InputReport* report);
// The summary line: DescribeOutcome, the orientation warning, "-> path".
std::string DescribeReport(const InputReport& report);
// One JSON object for scripts, version 1 (the fields: README.md, "Using
// the client").
std::string ReportJson(const InputReport& report);

}  // namespace dot::client

#endif  // DOT_CLIENT_REMOTE_CALL_H_
