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

FillOutcome FillRemote(v1::Triangulator::Stub& stub, const std::string& id,
                       const v1::FillOptions& options, const PolygonSoup& mesh,
                       double timeout_s, const FillProgressFn& on_progress) {
  const auto t0 = Clock::now();
  FillOutcome out;
  grpc::ClientContext context;
  context.set_deadline(
      std::chrono::system_clock::now() +
      std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000)));
  auto stream = stub.FillHoles(&context);
  wire::FillRequestWriter requests(id, options, mesh, kRequestBytes);
  v1::FillHolesRequest request;
  while (requests.Next(&request)) {
    if (!stream->Write(request)) break;  // the server answered early
  }
  stream->WritesDone();
  // Polygons or attributes kept come as a soup; plain triangles as before.
  const bool as_sent = options.answer() == v1::FILL_ANSWER_MESH &&
                       !options.dry_run() &&
                       (!mesh.attributes.empty() || options.keep_polygons());
  wire::MeshAssembler assembler;
  wire::SoupChunkReader soup(UINT32_MAX, UINT32_MAX);
  wire::PatchReader patches(mesh.vertices.size());
  size_t chunk = 0;
  v1::FillHolesResponse response;
  bool have_report = false;
  Status assembled = OkStatus();
  while (stream->Read(&response)) {
    switch (response.payload_case()) {
      case v1::FillHolesResponse::kProgress:
        if (on_progress) on_progress(response.progress());
        break;
      case v1::FillHolesResponse::kMesh:
        if (!assembled.ok()) break;
        assembled = as_sent ? soup.Add(response.mesh(),
                                       "mesh chunk " + std::to_string(chunk++))
                            : assembler.Add(response.mesh());
        break;
      case v1::FillHolesResponse::kPatch:
        if (assembled.ok()) assembled = patches.Add(response.patch());
        break;
      case v1::FillHolesResponse::kReport:
        out.report = response.report();
        have_report = true;
        break;
      default:
        break;
    }
  }
  out.status = stream->Finish();
  out.latency_ms = MsSince(t0);
  // A fill that stopped early still answers whole, then says why it
  // stopped; anything else that is not OK brings nothing to keep.
  out.partial = !out.status.ok() && have_report && out.report.stopped() > 0;
  if (!out.status.ok() && !out.partial) return out;
  if (!have_report) {
    out.status = grpc::Status(grpc::StatusCode::INTERNAL,
                              "the server ended the stream without a report");
    return out;
  }
  const size_t vertices =
      out.report.input_vertices() + out.report.added_vertices();
  const size_t faces = out.report.input_faces() + out.report.added_faces();
  out.notes.assign(out.report.notes().begin(), out.report.notes().end());
  if (assembled.ok() && as_sent) {
    assembled = soup.Finish(&out.soup);
    if (assembled.ok() && out.soup.vertices.size() != vertices) {
      assembled = InvalidArgument(std::to_string(out.soup.vertices.size()) +
                                  " vertices received, the report announced " +
                                  std::to_string(vertices));
    }
    // Polygons kept make fewer faces than the report's triangles.
    if (assembled.ok() && !options.keep_polygons() &&
        out.soup.faces.size() != faces) {
      assembled = InvalidArgument(std::to_string(out.soup.faces.size()) +
                                  " faces received, the report announced " +
                                  std::to_string(faces));
    }
    // A server that could not carry a channel says so in a note; one from
    // before attributes on the wire ignores them.
    for (const AttributeChannel& sent : mesh.attributes) {
      const bool answered = std::any_of(
          out.soup.attributes.begin(), out.soup.attributes.end(),
          [&](const AttributeChannel& a) { return a.name == sent.name; });
      const bool noted = std::any_of(
          out.notes.begin(), out.notes.end(), [&](const std::string& n) {
            return n.find("'" + sent.name + "'") != std::string::npos;
          });
      if (assembled.ok() && !answered && !noted) {
        out.notes.push_back("attribute '" + sent.name +
                            "' was not answered: the server predates "
                            "attributes on the wire (--local carries it)");
      }
    }
    out.as_sent = assembled.ok();
  } else if (assembled.ok() && options.answer() == v1::FILL_ANSWER_MESH &&
             !options.dry_run()) {  // a dry run's answer is the report alone
    assembled = assembler.Finish(vertices, faces, {}, &out.mesh);
  }
  out.patches = std::move(patches.patches());
  if (!assembled.ok()) {
    out.partial = false;
    out.status = grpc::Status(grpc::StatusCode::INTERNAL,
                              "bad mesh from the server: " + assembled.message);
  }
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
