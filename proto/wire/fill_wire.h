// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles on the wire: options to the core's FillOptions (the one place
// their defaults are applied), the report to its message, and the mesh
// split into request messages and put back together from them.
#ifndef DOT_PROTO_FILL_WIRE_H_
#define DOT_PROTO_FILL_WIRE_H_

#include <cstddef>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace dot::wire {

// Checks and maps the options; Options::memory_budget_bytes and the
// Delaunay backend are left to the caller (the server clamps them).
Status FillOptionsFromWire(const v1::FillOptions& wire, FillOptions* options);

void FillReportToWire(const FillReport& report, const RepairReport& repair,
                      size_t input_vertices, size_t input_faces,
                      v1::FillReport* out);

// The request stream of a mesh: the first message carries id and options,
// then vertices, then faces (polygons keep their corner counts), each
// message at most about `max_bytes`.
std::vector<v1::FillHolesRequest> MakeFillRequests(
    const std::string& id, const v1::FillOptions& options,
    const PolygonSoup& mesh, size_t max_bytes);

// Collects a request stream into a polygon soup, refusing (naming the
// message and the problem) what does not fit: partial coordinates, sizes
// that do not add up, more than `max_vertices` vertices or `max_faces`
// faces (or 3 x `max_faces` corners), polygons of more than 1000 corners.
class FillRequestReader {
 public:
  FillRequestReader(size_t max_vertices, size_t max_faces)
      : max_vertices_(max_vertices), max_faces_(max_faces) {}
  Status Add(const v1::FillHolesRequest& request);
  // The soup; indices are checked by the core (RepairMesh / FillHoles).
  Status Finish(PolygonSoup* soup);
  const std::string& id() const { return id_; }
  const v1::FillOptions& options() const { return options_; }
  // What has arrived so far.
  size_t vertices() const { return soup_.vertices.size(); }
  size_t faces() const { return soup_.faces.size(); }
  size_t messages() const { return messages_; }

 private:
  static constexpr uint32_t kMaxPolygonCorners = 1000;
  size_t max_vertices_, max_faces_;
  size_t messages_ = 0, corners_ = 0;
  std::string id_;
  v1::FillOptions options_;
  PolygonSoup soup_;
};

}  // namespace dot::wire

#endif  // DOT_PROTO_FILL_WIRE_H_
