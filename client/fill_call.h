// SPDX-License-Identifier: AGPL-3.0-or-later
// One FillHoles call, over the server or in this process, with the same
// outcome either way: the status, the report and the filled mesh.
#ifndef DOT_CLIENT_FILL_CALL_H_
#define DOT_CLIENT_FILL_CALL_H_

#include <grpcpp/support/status.h>

#include <functional>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace dot::client {

struct FillOutcome {
  grpc::Status status;  // of the RPC (or of the local run)
  // The fill stopped early (its time limit, a drain, a cancel) and status
  // says why, but the answer came whole: report, mesh and patches hold
  // every hole finished before the stop (report.stopped() the others).
  bool partial = false;
  v1::FillReport report;           // valid when status is OK or partial
  MeshData mesh;                   // the filled mesh (FILL_ANSWER_MESH)
  std::vector<SentPatch> patches;  // FILL_ANSWER_PATCHES
  // The filled mesh shaped as it was sent (its attribute channels, and
  // its polygons with keep_polygons), in place of `mesh`.
  PolygonSoup soup;
  bool as_sent = false;
  // What was not carried (attributes dropped, a file's unread parts): for
  // the text output and the JSON's "notes", after FillNotes'.
  std::vector<std::string> notes;
  double latency_ms = 0;
  std::string page;  // the viewer page written (fill-holes --report), or ""
};

// What a user should know about a fill besides its counts, one line each:
// what the repair changed, holes skipped by the selection, holes left
// open. For the JSON's "notes" and the text output.
std::vector<std::string> FillNotes(const v1::FillReport& report);

using FillProgressFn = std::function<void(const v1::FillProgress&)>;

// In this process: dot::FillSoup, the function the server runs (repair
// unless options.no_repair, then FillHoles), with the server's defaults.
// The soup is taken by value: move it in to hold the mesh once.
// `on_progress` gets the same reports a server sends, one at a time.
// The answer is `soup` (as_sent) when the mesh had attribute channels or
// options.keep_polygons kept its polygons, else `mesh`.
FillOutcome FillLocal(const std::string& id, const v1::FillOptions& options,
                      PolygonSoup mesh,
                      const FillProgressFn& on_progress = nullptr);

// The JSON object dotctl prints for a fill (--json): versioned, complete
// for every outcome (the `outcome` names of remote_call.h). `called`: a
// call (or local run) was made, so rpc_status is its code, not null;
// `error` is "" for ok.
std::string FillOutcomeJson(const std::string& input, const FillOutcome& o,
                            const std::string& output_path,
                            const std::string& outcome, int exit_code,
                            const std::string& error, bool called);

}  // namespace dot::client

#endif  // DOT_CLIENT_FILL_CALL_H_
