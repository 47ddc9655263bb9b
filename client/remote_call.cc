// SPDX-License-Identifier: AGPL-3.0-or-later
#include "remote_call.h"

#include <google/protobuf/util/json_util.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/json_envelope.h"
#include "wire/wire.h"

namespace dot::client {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

CallOutcome TriangulateLocal(const v1::TriangulateRequest& request,
                             DelaunayHelperPool* helpers) {
  const auto t0 = Clock::now();
  CallOutcome out;
  Problem problem;
  Options options;
  Status s = wire::ProblemFromRequest(request, &problem, &options);
  Control control;
  if (request.options().time_budget_ms() > 0) {
    control.deadline =
        t0 + std::chrono::milliseconds(request.options().time_budget_ms());
  }
  if (helpers != nullptr) {
    control.tetrahedralize = [&](const std::vector<Vec3>& points,
                                 Tetrahedralization* t) {
      return helpers->Tetrahedralize(points, t, nullptr, control.deadline,
                                     options.memory_budget_bytes);
    };
  }
  Result r;
  if (s.ok()) {
    r = Triangulate(problem, options, control);
    s = r.status;
  }
  if (s.ok() || s.code == StatusCode::kNoTriangulation) {
    wire::FillSummary(r, &out.summary);
    out.summary.set_compute_ms(r.stats.total_ms);
    out.mesh = {std::move(r.vertices), std::move(r.triangles)};
  } else {
    out.status = wire::ToGrpcStatus(s);
  }
  out.latency_ms = MsSince(t0);
  return out;
}

std::unique_ptr<DelaunayHelperPool> LocalDelaunayHelpers(int count) {
  if (!TetgenAvailable()) return nullptr;
  DelaunayHelperOptions helpers;
  helpers.count = count;
  // This dotctl, whatever its path (named by it in TetGen's messages).
  std::error_code ec;
  helpers.executable = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) helpers.executable = "/proc/self/exe";
  helpers.arguments = {kDelaunayHelperArgument};
  return std::make_unique<DelaunayHelperPool>(std::move(helpers));
}

std::string DescribeOutcome(const CallOutcome& o) {
  std::ostringstream s;
  if (!o.status.ok()) {
    s << wire::GrpcCodeName(o.status.error_code()) << ": "
      << o.status.error_message();
    return s.str();
  }
  const v1::Summary& m = o.summary;
  if (m.status() != v1::RESULT_STATUS_OK) {
    s << "no triangulation: " << m.message();
    return s.str();
  }
  char cost[64];
  std::snprintf(cost, sizeof cost, "%.6g", m.total_cost());
  s << "ok: " << m.triangle_count() << " triangles";
  if (m.loop_sizes_size() > 1) {
    s << " joining " << m.loop_sizes_size() << " loops";
    for (uint32_t l : m.reversed_loops()) s << " (loop " << l << " reversed)";
    if (m.bridges_size() > 0) {
      s << " by " << m.bridges_size() / 2
        << " bridges first (approximate: optimal for them)";
    }
  }
  s << ", " << m.solver() << " over " << m.search_space_used();
  if (!m.delaunay_backend().empty()) s << " (" << m.delaunay_backend() << ")";
  s << ", cost " << cost;
  if (m.cache_hit()) s << ", search space from cache";
  if (m.inserted_count() > 0) s << ", " << m.inserted_count() << " inserted";
  if (m.intersecting_pairs() > 0) {
    s << ", " << m.intersecting_pairs() << " SELF-INTERSECTING pairs";
  } else if (m.intersecting_pairs() == 0) {
    s << ", intersection-free (checked)";
  }
  char times[96];
  std::snprintf(times, sizeof times, ", %.1f ms compute, %.1f ms total",
                m.compute_ms(), o.latency_ms);
  s << times;
  return s.str();
}

std::string DescribeTiming(const CallOutcome& o) {
  char buf[160];
  if (o.status.ok()) {
    std::snprintf(buf, sizeof buf, "OK in %.1f ms (compute %.1f ms)",
                  o.latency_ms, o.summary.compute_ms());
  } else {
    std::snprintf(
        buf, sizeof buf, "%s in %.1f ms",
        std::string(wire::GrpcCodeName(o.status.error_code())).c_str(),
        o.latency_ms);
  }
  return buf;
}

void CheckOrientation(const MeshData& mesh, const std::vector<Vec3>& normals,
                      InputReport* report) {
  if (normals.empty() || mesh.triangles.empty()) return;
  int against = 0, checked = 0;
  const auto n = static_cast<int32_t>(normals.size());
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]],
               &c = mesh.vertices[t[2]];
    const Vec3 u{b.x - a.x, b.y - a.y, b.z - a.z},
        v{c.x - a.x, c.y - a.y, c.z - a.z};
    const Vec3 face{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z,
                    u.x * v.y - u.y * v.x};
    Vec3 given{0, 0, 0};
    for (const int32_t k : t) {
      if (k < n) {
        given.x += normals[k].x;
        given.y += normals[k].y;
        given.z += normals[k].z;
      }
    }
    const double d = face.x * given.x + face.y * given.y + face.z * given.z;
    if (d == 0 || !std::isfinite(d)) continue;
    ++checked;
    if (d < 0) ++against;
  }
  report->faces_against_normals = against;
  report->faces_checked = checked;
}

std::string DescribeReport(const InputReport& r) {
  std::string s = r.call ? DescribeOutcome(*r.call) : r.error;
  if (r.OrientationContradictsNormals()) {
    s += ", WARNING: " + std::to_string(r.faces_against_normals) + " of " +
         std::to_string(r.faces_checked) +
         " triangles face against the given normals (is the loop reversed?)";
  }
  if (!r.output.empty()) s += " -> " + (r.output == "-" ? "stdout" : r.output);
  return s;
}

std::string ReportJson(const InputReport& r) {
  JsonEnvelope e;
  e.input = r.input;
  e.outcome = r.outcome;
  e.exit_code = r.exit_code;
  if (r.call) e.rpc_status = r.call->status.error_code();
  e.error = r.error;
  e.output = r.output;
  e.latency_ms = r.call ? r.call->latency_ms : 0;
  e.notes = r.notes;
  std::string summary = "null";
  if (r.call && r.call->status.ok()) summary = ProtoJson(r.call->summary);
  e.fields = {
      {"faces_against_normals", r.faces_against_normals < 0
                                    ? "null"
                                    : std::to_string(r.faces_against_normals)},
      {"orientation_contradicts_normals",
       r.OrientationContradictsNormals() ? "true" : "false"},
      {"summary", summary}};
  return e.ToJson();
}

}  // namespace dot::client
