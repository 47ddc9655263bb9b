// SPDX-License-Identifier: AGPL-3.0-or-later
// The FillHoles use case, with no stream in it: the request's options
// checked once and put under the server's limits, the fill itself
// (dot::FillSoup, the function dotctl --local and the benchmark run too),
// and the answer as response messages, made one at a time: the filled mesh
// in chunks (its polygons and attribute channels with them, when kept) or
// only the patches (FILL_ANSWER_PATCHES), then the report.
// The reactor reads, admits, starts and writes; this is what it runs.
#ifndef DOT_SERVER_RPC_FILL_HOLES_CALL_H_
#define DOT_SERVER_RPC_FILL_HOLES_CALL_H_

#include <optional>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "rpc/service_options.h"
#include "wire/fill_wire.h"
#include "wire/wire.h"

namespace dot::server {

class FillHolesCall {
 public:
  // The first message's options: not OK names what is wrong with them.
  // Each hole runs with the server's solve options and limits
  // (ApplyServerLimits), `threads` holes at once.
  Status Configure(const v1::FillOptions& wire, const ServiceOptions& server,
                   int threads);
  // The fill, on a compute thread: the status of dot::FillSoup. `log`
  // receives the call's log detail (what arrived, then what was filled).
  Status Run(PolygonSoup soup, const Control& control,
             const FillProgressFn& on_progress, std::string* log);
  // Run stopped early but kept what it filled (FillResult::partial): the
  // answer is still made, and the call ends with Run's status after it.
  bool partial() const { return result_.fill.partial; }
  // After a Run that succeeded or is partial: the next message of the
  // answer, tagged `id`; the last one (done() after it) is the report.
  void Next(const std::string& id, size_t chunk_bytes,
            v1::FillHolesResponse* message);
  bool done() const { return done_; }

 private:
  FillOptions options_;
  v1::FillAnswer answer_ = v1::FILL_ANSWER_MESH;
  SoupFillResult result_;
  std::vector<SentPatch> patches_;  // FILL_ANSWER_PATCHES
  std::optional<wire::MeshChunker> chunks_;
  std::optional<wire::SoupChunkWriter> soup_chunks_;  // result_.soup's
  std::optional<wire::PatchWriter> patch_writer_;
  bool done_ = false;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_FILL_HOLES_CALL_H_
