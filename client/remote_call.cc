// SPDX-License-Identifier: AGPL-3.0-or-later
#include "remote_call.h"

#include <google/protobuf/util/json_util.h>

#include <chrono>
#include <cstdio>
#include <sstream>

#include "wire/wire.h"

namespace dot::client {
namespace {
using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
}  // namespace

CallOutcome TriangulateRemote(
    v1::Triangulator::Stub& stub, const v1::TriangulateRequest& request,
    const std::vector<Vec3>& input, double timeout_s,
    const std::function<void(const v1::Progress&)>& on_progress) {
  const auto t0 = Clock::now();
  CallOutcome out;
  grpc::ClientContext context;
  context.set_deadline(
      std::chrono::system_clock::now() +
      std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000)));
  auto reader = stub.Triangulate(&context, request);
  v1::TriangulateResponse msg;
  wire::MeshAssembler assembler;
  bool have_summary = false;
  Status assembly = OkStatus();
  while (reader->Read(&msg)) {
    if (msg.has_progress() && on_progress) on_progress(msg.progress());
    if (msg.has_mesh() && assembly.ok()) assembly = assembler.Add(msg.mesh());
    if (msg.has_summary()) {
      out.summary = msg.summary();
      have_summary = true;
    }
  }
  out.status = reader->Finish();
  if (out.status.ok() && !have_summary) {
    out.status = {grpc::StatusCode::DATA_LOSS,
                  "stream ended without a summary"};
  }
  if (out.status.ok() && assembly.ok() &&
      out.summary.status() == v1::RESULT_STATUS_OK) {
    assembly = assembler.Finish(out.summary, input, &out.mesh);
  }
  if (out.status.ok() && !assembly.ok()) {
    out.status = {grpc::StatusCode::DATA_LOSS, assembly.message};
  }
  out.latency_ms = MsSince(t0);
  return out;
}

CallOutcome TriangulateLocal(const v1::TriangulateRequest& request) {
  const auto t0 = Clock::now();
  CallOutcome out;
  Problem problem;
  Options options;
  Status s = wire::ProblemFromRequest(request, &problem, &options);
  Result r;
  if (s.ok()) {
    r = Triangulate(problem, options);
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
  s << "ok: " << m.triangle_count() << " triangles, " << m.solver() << " over "
    << m.search_space_used();
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

std::string JsonQuote(const std::string& in) {
  std::string out = "\"";
  for (const char c : in) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string OutcomeJson(const std::string& name, const CallOutcome& o,
                        const std::string& output_path) {
  std::string summary = "null";
  if (o.status.ok()) {
    google::protobuf::util::JsonPrintOptions options;
    options.always_print_primitive_fields = true;
    options.preserve_proto_field_names = true;
    summary.clear();
    (void)google::protobuf::util::MessageToJsonString(o.summary, &summary,
                                                      options);
  }
  std::ostringstream s;
  s << "{\"input\":" << JsonQuote(name) << ",\"rpc_status\":"
    << JsonQuote(std::string(wire::GrpcCodeName(o.status.error_code())))
    << ",\"error\":" << JsonQuote(o.status.error_message())
    << ",\"output\":" << JsonQuote(output_path)
    << ",\"latency_ms\":" << o.latency_ms << ",\"summary\":" << summary << "}";
  return s.str();
}

}  // namespace dot::client
