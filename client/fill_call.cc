// SPDX-License-Identifier: AGPL-3.0-or-later
#include "fill_call.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <utility>

#include "cli/json_envelope.h"
#include "remote_call.h"
#include "wire/fill_wire.h"
#include "wire/soup_wire.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

using Clock = std::chrono::steady_clock;

// Requests stay well under gRPC's default 4 MiB message limit.
constexpr size_t kRequestBytes = 1 << 20;

}  // namespace

FillOutcome FillLocal(const std::string&, const v1::FillOptions& wire_options,
                      PolygonSoup soup, const FillProgressFn& on_progress) {
  const auto t0 = Clock::now();
  FillOutcome out;
  FillOptions options;
  const Status s = wire::FillOptionsFromWire(wire_options, &options);
  if (!s.ok()) {
    out.status = wire::ToGrpcStatus(s);
    return out;
  }
  // The request's time budget holds here as on a server.
  Control control;
  if (wire_options.time_budget_ms() > 0) {
    control.deadline =
        t0 + std::chrono::milliseconds(wire_options.time_budget_ms());
  }
  v1::FillAnswer answer;
  const Status a = wire::FillAnswerFromWire(wire_options, &answer);
  if (!a.ok()) {
    out.status = wire::ToGrpcStatus(a);
    return out;
  }
  const auto sent_vertices = static_cast<int64_t>(soup.vertices.size());
  dot::FillProgressFn on_phase;
  wire::FillProgressClock clock(t0);
  if (on_progress) {
    on_phase = [&](FillPhase phase, int done, int total) {
      on_progress(clock.Report(phase, done, total));
    };
  }
  SoupFillResult r = FillSoup(std::move(soup), options, control, on_phase);
  out.notes = std::move(r.notes);
  out.status = wire::ToGrpcStatus(r.fill.status);
  if (r.fill.status.code == StatusCode::kDeadlineExceeded) {
    out.status =
        grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                     "the time limit (--time-budget-ms " +
                         std::to_string(wire_options.time_budget_ms()) +
                         ") passed: " + r.fill.status.message);
  }
  out.partial = r.fill.partial;
  if (r.fill.status.ok() || r.fill.partial) {
    wire::FillReportToWire(r.fill.report, r.repair,
                           static_cast<size_t>(r.input_vertices),
                           static_cast<size_t>(r.input_faces), &out.report);
    for (const std::string& note : out.notes) out.report.add_notes(note);
    if (answer == v1::FILL_ANSWER_PATCHES) {
      out.patches = PatchesAsSent(r, sent_vertices);
      if (static_cast<int>(out.patches.size()) != r.fill.report.filled) {
        out.status = grpc::Status(grpc::StatusCode::INTERNAL,
                                  "the filled mesh is not laid out as its "
                                  "patches need");
        out.partial = false;
      }
    } else if (!r.soup.faces.empty()) {
      out.soup = std::move(r.soup);
      out.as_sent = true;
    } else {
      out.mesh = std::move(r.fill.mesh);
    }
  }
  out.latency_ms = MsSince(t0);
  return out;
}

std::vector<std::string> FillNotes(const v1::FillReport& r) {
  std::vector<std::string> notes;
  const v1::RepairReport& rep = r.repair();
  std::string repaired;
  auto add = [&repaired](uint32_t n, const char* what) {
    if (n == 0) return;
    repaired += (repaired.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(rep.merged_vertices(), "duplicate vertices merged");
  add(rep.degenerate_faces(), "degenerate faces dropped");
  add(rep.duplicate_faces(), "duplicate faces dropped");
  add(rep.triangulated_polygons(), "polygons triangulated");
  add(rep.reoriented_faces(), "faces reoriented");
  if (!repaired.empty()) notes.push_back("repair: " + repaired);
  if (rep.non_manifold_vertices() > 0) {
    notes.push_back(std::to_string(rep.non_manifold_vertices()) +
                    " non-manifold vertices kept (their loops are split)");
  }
  if (r.skipped() > 0) {
    notes.push_back(std::to_string(r.skipped()) +
                    " holes skipped by the selection");
  }
  if (r.unfilled() > 0) {
    notes.push_back(std::to_string(r.unfilled()) +
                    " holes left open: see each hole's reason");
  }
  const auto crossing = std::count_if(
      r.holes().begin(), r.holes().end(), [](const v1::HoleReport& h) {
        return h.status() == v1::HOLE_STATUS_FILLED &&
               h.intersecting_pairs() > 0;
      });
  if (crossing > 0) {
    notes.push_back(std::to_string(crossing) +
                    " holes filled with patches that meet the mesh where it "
                    "already intersects itself (--allow-input-intersections)");
  }
  if (r.stopped() > 0) {
    notes.push_back(std::to_string(r.stopped()) +
                    " holes not filled: the fill stopped before them");
  }
  return notes;
}

std::string FillOutcomeJson(const std::string& input, const FillOutcome& o,
                            const std::string& output_path,
                            const std::string& outcome, int exit_code,
                            const std::string& error, bool called) {
  JsonEnvelope e;
  e.input = input;
  e.outcome = outcome;
  e.exit_code = exit_code;
  if (called) e.rpc_status = o.status.error_code();
  e.error = error;
  e.output = output_path;
  e.latency_ms = o.latency_ms;
  const bool answered = called && (o.status.ok() || o.partial);
  if (answered) e.notes = FillNotes(o.report);
  e.notes.insert(e.notes.end(), o.notes.begin(), o.notes.end());
  e.fields = {
      {"report", answered ? ProtoJson(o.report) : std::string("null")},
      {"page", o.page.empty() ? std::string("null") : JsonQuote(o.page)}};
  return e.ToJson();
}

}  // namespace dot::client
