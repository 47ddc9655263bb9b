// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: a dot.v1.TriangulateRequest from raw protobuf bytes,
// through what dot-server does with it (server/rpc/job.cc, JobRunner::Admit
// and Run; server/rpc/job_response.cc): parse, cap the id, translate with
// wire::ProblemFromRequest, clamp the memory and time budgets, and for tiny
// polygons (at most 12 vertices) solve with dot::Triangulate under a short
// deadline, then stream the answer back as the server would (mesh chunks,
// summary), serialized, parsed again and reassembled as dotctl does.
//
// Oracle: never crash; every refusal is a non-OK status with a message; an
// OK answer validates (a disk bounded by the polygon, intersection-free
// unless SEARCH_SPACE_ALL was asked for); the reassembled mesh is the
// result's.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "google/protobuf/stubs/logging.h"
#include "tetgen_child.h"
#include "wire/wire.h"
#include "wire_oracle.h"

namespace v1 = dot::v1;

namespace {

// As dot-server: request ids of at most this many bytes (server/rpc/job.h).
constexpr size_t kMaxRequestIdBytes = 256;
// Polygons this fuzzer solves; larger valid ones stop after translation.
constexpr size_t kMaxSolvedVertices = 12;
constexpr uint32_t kDeadlineMs = 200;

using dot::fuzz::Fail;

void CheckRefusal(const dot::Status& s) {
  dot::fuzz::CheckRefusal(s, /*no_triangulation_is_ok=*/true);
}

void CheckMesh(const dot::Options& options, const dot::Result& r) {
  const dot::MeshReport report =
      dot::ValidateMesh(r.vertices, r.polygon, r.triangles, false);
  if (!report.valid()) Fail("invalid mesh: " + report.first_problem);
  // 'all' and 'delaunay_first' may answer a self-intersecting optimum.
  if (options.space != dot::SearchSpace::kAll &&
      options.space != dot::SearchSpace::kDelaunayFirst &&
      dot::CountIntersectingPairs(r.vertices, r.triangles) != 0) {
    Fail("self-intersecting OK result");
  }
}

// The response stream of JobResponse, through the wire and back.
void CheckResponse(const v1::TriangulateRequest& request,
                   const dot::Problem& problem, const dot::Result& r) {
  const size_t first =
      request.options().omit_input_vertices() ? problem.vertices.size() : 0;
  // Small chunks, so that most meshes take several.
  const size_t chunk_bytes = 1 + request.id().size() % 97;
  dot::wire::MeshChunker chunker(r, first, chunk_bytes);
  dot::wire::MeshAssembler assembler;
  v1::TriangulateResponse message, received;
  std::string bytes;
  for (int count = 0;; ++count) {
    if (count > 100000) Fail("endless chunks");
    message.Clear();
    message.set_id(request.id());
    if (!chunker.Next(message.mutable_mesh())) break;
    if (!message.SerializeToString(&bytes)) Fail("chunk does not serialize");
    if (!received.ParseFromString(bytes)) Fail("chunk does not parse");
    const dot::Status s = assembler.Add(received.mesh());
    if (!s.ok()) Fail("chunk refused: " + s.message);
  }
  message.Clear();
  dot::wire::FillSummary(r, message.mutable_summary());
  if (!message.SerializeToString(&bytes)) Fail("summary does not serialize");
  if (!received.ParseFromString(bytes)) Fail("summary does not parse");
  dot::MeshData mesh;
  const dot::Status s =
      assembler.Finish(received.summary(), problem.vertices, &mesh);
  if (!s.ok()) Fail("mesh not reassembled: " + s.message);
  if (mesh.triangles != r.triangles) Fail("other triangles received");
  if (mesh.vertices.size() != r.vertices.size() ||
      std::memcmp(mesh.vertices.data(), r.vertices.data(),
                  r.vertices.size() * sizeof(dot::Vec3)) != 0) {
    Fail("other vertices received");
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Invalid UTF-8 in a string field is a parse failure, logged each time.
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  v1::TriangulateRequest request;
  if (!request.ParseFromArray(data, static_cast<int>(size))) return 0;
  if (request.id().size() > kMaxRequestIdBytes) return 0;  // refused so

  dot::Problem problem;
  dot::Options options;  // the server's defaults
  const dot::Status shape =
      dot::wire::ProblemFromRequest(request, &problem, &options);
  if (!shape.ok()) {
    CheckRefusal(shape);
    return 0;
  }
  if (problem.vertices.size() > kMaxSolvedVertices) return 0;

  const uint64_t asked = request.options().memory_budget_bytes();
  const auto cap = static_cast<uint64_t>(options.memory_budget_bytes);
  options.memory_budget_bytes =
      static_cast<int64_t>(asked > 0 ? std::min(asked, cap) : cap);
  const uint32_t budget_ms = request.options().time_budget_ms();
  dot::Control control;
  control.deadline =
      std::chrono::steady_clock::now() +
      std::chrono::milliseconds(budget_ms > 0 ? std::min(budget_ms, kDeadlineMs)
                                              : kDeadlineMs);
  if (request.options().progress_interval_ms() > 0) {
    control.progress = [](dot::Stage stage, double fraction) {
      v1::Progress p;
      p.set_stage(dot::wire::ToWire(stage));
      p.set_fraction(fraction);
      if (!(fraction >= 0 && fraction <= 1)) Fail("progress out of [0, 1]");
    };
  }
  // TetGen runs in a helper process, as in dot-server (its default).
  control.tetrahedralize = dot::fuzz::TetgenInChild;
  dot::SpaceCache cache(int64_t{16} << 20);
  if (!request.options().no_cache()) control.space_cache = &cache;

  const dot::Result r = dot::Triangulate(problem, options, control);
  if (r.status.ok()) {
    CheckMesh(options, r);
  } else {
    CheckRefusal(r.status);
  }
  if (r.status.ok() || r.status.code == dot::StatusCode::kNoTriangulation) {
    CheckResponse(request, problem, r);
  }
  return 0;
}
