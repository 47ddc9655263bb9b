// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles on the wire: options to the core's FillOptions (the one place
// their defaults are applied), the report to its message, and the mesh
// split into request messages and put back together from them.
#ifndef DOT_PROTO_FILL_WIRE_H_
#define DOT_PROTO_FILL_WIRE_H_

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "wire/soup_wire.h"

namespace dot::wire {

// Checks and maps the options; Options::memory_budget_bytes and the
// Delaunay backend are left to the caller (the server clamps them).
// FillOptions.answer is the transport's (see FillAnswerFromWire).
Status FillOptionsFromWire(const v1::FillOptions& wire, FillOptions* options);
// The answer asked for; kInvalidArgument for a value this server does not
// know.
Status FillAnswerFromWire(const v1::FillOptions& wire, v1::FillAnswer* answer);

void FillReportToWire(const FillReport& report, const RepairReport& repair,
                      size_t input_vertices, size_t input_faces,
                      v1::FillReport* out);
// The stage of a FillHoles or SurfaceNetwork request (unset: kFair);
// kInvalidArgument for a value this server does not know.
Status FillStageFromWire(v1::FillStage wire, FillStage* stage);
v1::HoleStatus HoleStatusToWire(HoleStatus status);
v1::Escalation EscalationToWire(Escalation escalation);
v1::FillPhase FillPhaseToWire(FillPhase phase);
// Back; an unknown value (a newer server's) reads as kHoles.
FillPhase FillPhaseFromWire(v1::FillPhase phase);

// One fill's progress reports as messages (the server's and dotctl
// --local's alike): the phase, the holes, the time since `start` and, in
// the holes phase, the time left at the pace since that phase began.
// Called one report at a time, as FillProgressFn is.
class FillProgressClock {
 public:
  explicit FillProgressClock(std::chrono::steady_clock::time_point start)
      : start_(start) {}
  v1::FillProgress Report(FillPhase phase, int holes_done, int holes_total);

 private:
  std::chrono::steady_clock::time_point start_, holes_start_;
  bool in_holes_ = false;
};

// Back, for clients that print the core's names (an unknown value reads
// as kFailed / kNone).
HoleStatus HoleStatusFromWire(v1::HoleStatus status);
Escalation EscalationFromWire(v1::Escalation escalation);

// The request stream of a mesh, built one message at a time as the stream
// asks (an upload never holds a second copy of the mesh): the first message
// carries id and options with the first slice, then SoupChunkWriter's
// slices (vertices, faces, attribute channels), each message at most about
// `max_bytes`. `mesh` must outlive the writer.
class FillRequestWriter {
 public:
  FillRequestWriter(std::string id, v1::FillOptions options,
                    const PolygonSoup& mesh, size_t max_bytes);
  // The next message; false once every one has been given.
  bool Next(v1::FillHolesRequest* request);

 private:
  std::string id_;
  v1::FillOptions options_;
  SoupChunkWriter chunks_;
  bool first_ = true;
};

// Patches (FILL_ANSWER_PATCHES) to messages of at most about `max_bytes`;
// a patch larger than that continues over several messages.
class PatchWriter {
 public:
  PatchWriter(const std::vector<SentPatch>& patches, size_t max_bytes)
      : patches_(&patches), max_bytes_(std::max<size_t>(1, max_bytes)) {}
  bool Next(v1::HolePatch* message);

 private:
  const std::vector<SentPatch>* patches_;
  size_t max_bytes_;
  size_t patch_ = 0, vertex_ = 0, face_ = 0, replaced_ = 0;
  size_t piece_ = 0;  // replacement triangles given so far
};

// Reassembles the patches of a FillHoles answer, checking that each message
// continues the last: a patch's messages one after another, its vertices
// numbered on; the first patch's new vertices right after the
// `sent_vertices` the client sent, each next patch's after the last one's;
// holes in increasing id order; faces over vertices that exist by then.
class PatchReader {
 public:
  explicit PatchReader(size_t sent_vertices) : next_vertex_(sent_vertices) {}
  Status Add(const v1::HolePatch& message);
  std::vector<SentPatch>& patches() { return patches_; }

 private:
  size_t next_vertex_;  // the id the next new vertex must have
  std::vector<SentPatch> patches_;
};

// Collects a request stream into a polygon soup (SoupChunkReader, which
// names what does not fit), id and options from the first message.
class FillRequestReader {
 public:
  FillRequestReader(size_t max_vertices, size_t max_faces)
      : chunks_(max_vertices, max_faces) {}
  Status Add(const v1::FillHolesRequest& request);
  // The soup; indices are checked by the core (RepairMesh / FillHoles).
  Status Finish(PolygonSoup* soup);
  const std::string& id() const { return id_; }
  const v1::FillOptions& options() const { return options_; }
  // What has arrived so far.
  size_t vertices() const { return chunks_.vertices(); }
  size_t faces() const { return chunks_.faces(); }
  int64_t attribute_bytes() const { return chunks_.attribute_bytes(); }
  size_t channels() const { return chunks_.channels(); }
  size_t corners() const { return chunks_.corners(); }
  size_t messages() const { return messages_; }

 private:
  size_t messages_ = 0;
  std::string id_;
  v1::FillOptions options_;
  SoupChunkReader chunks_;
};

}  // namespace dot::wire

#endif  // DOT_PROTO_FILL_WIRE_H_
