// SPDX-License-Identifier: AGPL-3.0-or-later
// SurfaceNetwork on the wire: options to the core's SurfaceOptions (the one
// place their defaults are applied), the report to its message, and the
// network as MeshChunk slices whose faces are its polylines.
#ifndef DOT_PROTO_SURFACE_WIRE_H_
#define DOT_PROTO_SURFACE_WIRE_H_

#include <string>

#include "dot/dot.h"
#include "dot/network.h"
#include "dot/v1/triangulation.pb.h"
#include "wire/soup_wire.h"

namespace dot::wire {

// Checks and maps the options; Options::memory_budget_bytes and the
// Delaunay backend are left to the caller (the server clamps them).
Status SurfaceOptionsFromWire(const v1::SurfaceOptions& wire,
                              SurfaceOptions* options);
// `mesh`: the surface the report goes with (its sizes are announced).
void SurfaceReportToWire(const SurfaceReport& report, size_t input_vertices,
                         const MeshData& mesh, v1::SurfaceReport* out);
v1::PatchStatus PatchStatusToWire(PatchStatus status);
// Back; an unknown value (a newer server's) reads as kFailed.
PatchStatus PatchStatusFromWire(v1::PatchStatus status);

// A network as a soup (polylines as faces, normals as the per-vertex
// channel "normal") and back; NetworkFromSoup refuses another channel or a
// per-corner "normal".
PolygonSoup SoupFromNetwork(const CurveNetwork& network);
Status NetworkFromSoup(PolygonSoup soup, CurveNetwork* network);

// The request stream of a network, one message at a time: id and options
// with the first slice, then SoupChunkWriter's slices. `soup` (the
// network's, SoupFromNetwork) must outlive the writer.
class SurfaceRequestWriter {
 public:
  SurfaceRequestWriter(std::string id, v1::SurfaceOptions options,
                       const PolygonSoup& soup, size_t max_bytes);
  bool Next(v1::SurfaceNetworkRequest* request);

 private:
  std::string id_;
  v1::SurfaceOptions options_;
  SoupChunkWriter chunks_;
  bool first_ = true;
};

// Collects a request stream into a network, id and options from the first
// message, refusing (naming the message) what does not fit the limits.
class SurfaceRequestReader {
 public:
  SurfaceRequestReader(size_t max_vertices, size_t max_polylines)
      : chunks_(max_vertices, max_polylines, /*polylines=*/true) {}
  Status Add(const v1::SurfaceNetworkRequest& request);
  Status Finish(CurveNetwork* network);
  const std::string& id() const { return id_; }
  const v1::SurfaceOptions& options() const { return options_; }
  size_t vertices() const { return chunks_.vertices(); }
  size_t polylines() const { return chunks_.faces(); }
  size_t points() const { return chunks_.corners(); }  // over polylines
  size_t messages() const { return messages_; }

 private:
  size_t messages_ = 0;
  std::string id_;
  v1::SurfaceOptions options_;
  SoupChunkReader chunks_;
};

}  // namespace dot::wire

#endif  // DOT_PROTO_SURFACE_WIRE_H_
