// SPDX-License-Identifier: AGPL-3.0-or-later
#include "surface_call.h"

#include <chrono>

#include "cli/json_envelope.h"
#include "wire/surface_wire.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kRequestBytes = 1 << 20;  // well under gRPC's 4 MiB

}  // namespace

SurfaceOutcome SurfaceLocal(const v1::SurfaceOptions& wire_options,
                            const CurveNetwork& network,
                            const SurfaceProgressFn& on_progress) {
  const auto t0 = Clock::now();
  SurfaceOutcome out;
  SurfaceOptions options;
  const Status s = wire::SurfaceOptionsFromWire(wire_options, &options);
  if (!s.ok()) {
    out.status = wire::ToGrpcStatus(s);
    return out;
  }
  Control control;
  if (wire_options.time_budget_ms() > 0) {
    control.deadline =
        t0 + std::chrono::milliseconds(wire_options.time_budget_ms());
  }
  dot::SurfaceProgressFn progress;
  if (on_progress) {
    progress = [&](int done, int total) {
      v1::SurfaceProgress p;
      p.set_patches_done(static_cast<uint32_t>(done));
      p.set_patches_total(static_cast<uint32_t>(total));
      p.set_elapsed_ms(MsSince(t0));
      on_progress(p);
    };
  }
  SurfaceResult r = SurfaceNetwork(network, options, control, progress);
  out.status = wire::ToGrpcStatus(r.status);
  if (r.status.ok()) {
    wire::SurfaceReportToWire(r.report, network.vertices.size(), r.mesh,
                              &out.report);
    out.mesh = std::move(r.mesh);
  }
  out.latency_ms = MsSince(t0);
  return out;
}

std::vector<std::string> SurfaceNotes(const v1::SurfaceReport& r) {
  std::vector<std::string> notes;
  if (r.merged_vertices() > 0) {
    notes.push_back(std::to_string(r.merged_vertices()) +
                    " points welded to an earlier one (at the same place, or "
                    "within --weld)");
  }
  if (r.dangling_size() > 0) {
    notes.push_back(std::to_string(r.dangling_size()) +
                    " dangling curves (an end no other curve meets) bound "
                    "no patch");
  }
  if (r.failed() > 0) {
    notes.push_back(std::to_string(r.failed()) +
                    (r.failed() == 1 ? " patch" : " patches") +
                    " left open: see each patch's reason");
  }
  if (r.non_manifold_curves() > 0) {
    notes.push_back(std::to_string(r.non_manifold_curves()) +
                    " curves border more than two patches: the surface is "
                    "non-manifold along them");
  }
  for (const std::string& n : r.notes()) notes.push_back(n);
  return notes;
}

std::string SurfaceOutcomeJson(const std::string& input,
                               const SurfaceOutcome& o,
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
  const bool answered = called && o.status.ok();
  if (answered) e.notes = SurfaceNotes(o.report);
  e.fields = {{"report", answered ? ProtoJson(o.report) : std::string("null")}};
  return e.ToJson();
}

}  // namespace dot::client
