// SPDX-License-Identifier: AGPL-3.0-or-later
// Translation between the dot.v1 wire messages and the core library's types,
// shared by server and client: requests to problems, results to summaries
// and mesh chunks, chunks back to meshes, and status codes both ways.
#ifndef DOT_PROTO_WIRE_H_
#define DOT_PROTO_WIRE_H_

#include <grpcpp/support/status.h>

#include <cstddef>
#include <functional>
#include <string>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace dot::wire {

// Shape checks (coordinate counts) and the mapping itself; value checks
// (finite, duplicates, ...) are the core's.
Status ProblemFromRequest(const v1::TriangulateRequest& request,
                          Problem* problem, Options* options);

v1::TriangulateRequest MakeRequest(const std::string& id,
                                   const PolygonData& polygon,
                                   const MetricWeights& weights,
                                   const v1::Options& options);

v1::MetricWeights ToWire(const MetricValues& values);
MetricValues FromWire(const v1::MetricWeights& w);
SearchSpace FromWire(v1::SearchSpace s);
v1::Stage ToWire(Stage s);

void FillSummary(const Result& result, v1::Summary* summary);

// Splits a result's mesh into chunks of at most about `max_bytes` each:
// vertices from `first_vertex` on, then triangles. Made one at a time, so a
// large mesh is never held twice. `result` must outlive the chunker.
class MeshChunker {
 public:
  MeshChunker(const Result& result, size_t first_vertex, size_t max_bytes)
      : MeshChunker(result.vertices, result.triangles, first_vertex,
                    max_bytes) {}
  // Any mesh; both vectors must outlive the chunker.
  MeshChunker(const std::vector<Vec3>& vertices,
              const std::vector<Triangle>& triangles, size_t first_vertex,
              size_t max_bytes);
  // Fills the next chunk; false once every chunk has been given.
  bool Next(v1::MeshChunk* chunk);

 private:
  const std::vector<Vec3>* vertices_;  // pointers: chunkers are movable
  const std::vector<Triangle>* triangles_;
  size_t next_vertex_, next_triangle_ = 0;
  size_t vertices_per_chunk_, triangles_per_chunk_;
};

// Reassembles a mesh from chunks; the summary says how big it must be.
class MeshAssembler {
 public:
  Status Add(const v1::MeshChunk& chunk);
  // Checks completeness against the summary; vertices the server omitted
  // (omit_input_vertices) are taken from `input`.
  Status Finish(const v1::Summary& summary, const std::vector<Vec3>& input,
                MeshData* mesh) {
    return Finish(summary.vertex_count(), summary.triangle_count(), input,
                  mesh);
  }
  Status Finish(size_t vertex_count, size_t triangle_count,
                const std::vector<Vec3>& input, MeshData* mesh);

 private:
  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  size_t first_vertex_ = 0;
  bool started_ = false;
};

grpc::StatusCode ToGrpcCode(StatusCode code);
grpc::Status ToGrpcStatus(const Status& status);
std::string_view GrpcCodeName(grpc::StatusCode code);

}  // namespace dot::wire

#endif  // DOT_PROTO_WIRE_H_
