// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/fill_holes_call.h"

namespace dot::server {

Status FillHolesCall::Configure(const v1::FillOptions& wire,
                                const ServiceOptions& server, int threads) {
  Status s = wire::FillOptionsFromWire(wire, &options_);
  if (s.ok()) s = wire::FillAnswerFromWire(wire, &answer_);
  if (!s.ok()) return s;
  ApplyServerLimits(server, wire.memory_budget_bytes(), threads, &options_);
  return CheckFillOptions(options_);
}

Status FillHolesCall::Run(PolygonSoup soup, const Control& control,
                          const FillProgressFn& on_progress, std::string* log) {
  // What the log says if the fill stops before it has more to say.
  *log = "received_vertices=" + std::to_string(soup.vertices.size()) +
         " received_faces=" + std::to_string(soup.faces.size());
  const auto sent_vertices = static_cast<int64_t>(soup.vertices.size());
  result_ = FillSoup(std::move(soup), options_, control, on_progress);
  if (options_.dry_run) {
    result_.fill.mesh = {};  // the report is the answer
    result_.soup = {};
  } else if ((result_.fill.status.ok() || result_.fill.partial) &&
             answer_ == v1::FILL_ANSWER_PATCHES) {
    patches_ = PatchesAsSent(result_, sent_vertices);
    if (static_cast<int>(patches_.size()) != result_.fill.report.filled) {
      result_.fill.status = MakeStatus(
          StatusCode::kInternal,
          "the filled mesh is not laid out as its patches need; ask for the "
          "whole mesh (FILL_ANSWER_MESH)");
      result_.fill.partial = false;
    }
    result_.fill.mesh = {};  // the patches are the answer
    result_.soup = {};
  }
  const FillReport& r = result_.fill.report;
  if (result_.input_faces > 0) {
    *log = "vertices=" + std::to_string(result_.input_vertices) +
           " faces=" + std::to_string(result_.input_faces) +
           " holes=" + std::to_string(r.loops) +
           " filled=" + std::to_string(r.filled) +
           (r.stopped > 0 ? " stopped=" + std::to_string(r.stopped) : "") +
           " added_faces=" + std::to_string(r.added_faces);
  }
  return result_.fill.status;
}

void FillHolesCall::Next(const std::string& id, size_t chunk_bytes,
                         v1::FillHolesResponse* message) {
  if (!chunks_) {
    chunks_.emplace(result_.fill.mesh.vertices, result_.fill.mesh.triangles, 0,
                    chunk_bytes);
    soup_chunks_.emplace(result_.soup, chunk_bytes);
    patch_writer_.emplace(patches_, chunk_bytes);
  }
  message->Clear();
  message->set_id(id);
  if (chunks_->Next(message->mutable_mesh()) ||
      soup_chunks_->Next(message->mutable_mesh()) ||
      patch_writer_->Next(message->mutable_patch())) {
    return;
  }
  wire::FillReportToWire(result_.fill.report, result_.repair,
                         static_cast<size_t>(result_.input_vertices),
                         static_cast<size_t>(result_.input_faces),
                         message->mutable_report());
  for (const std::string& note : result_.notes) {
    message->mutable_report()->add_notes(note);
  }
  done_ = true;
}

}  // namespace dot::server
