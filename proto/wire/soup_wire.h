// SPDX-License-Identifier: AGPL-3.0-or-later
// A polygon soup with its attribute channels as MeshChunk slices, in either
// direction (FillHoles uploads, and answers that keep polygons or carry
// attributes): vertices, then faces (with their corner counts when some
// face is not a triangle), then each channel's values and (per corner)
// indices, each slice at most about `max_bytes`.
#ifndef DOT_PROTO_SOUP_WIRE_H_
#define DOT_PROTO_SOUP_WIRE_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace dot::wire {

// Made one slice at a time as the stream asks: the soup is never held
// twice. `soup` must outlive the writer.
class SoupChunkWriter {
 public:
  SoupChunkWriter(const PolygonSoup& soup, size_t max_bytes);
  // The next slice; false once every one has been given.
  bool Next(v1::MeshChunk* chunk);

 private:
  const PolygonSoup* soup_;
  bool all_triangles_ = true;
  size_t max_bytes_;
  size_t next_vertex_ = 0, next_face_ = 0;
  size_t channel_ = 0, next_value_ = 0, next_index_ = 0;
};

// Collects slices into a soup, refusing (naming the slice and the problem)
// what does not fit: slices out of order, partial coordinates, sizes that
// do not add up, more than `max_vertices` vertices or `max_faces` faces (or
// 3 x `max_faces` corners), polygons of more than 1000 corners, channels
// that are not well formed (see CheckAttributes) or more than 16 of them.
// With `polylines`, the faces are the polylines of a curve network: at
// least 2 points each, and as many as the corner limit allows.
class SoupChunkReader {
 public:
  SoupChunkReader(size_t max_vertices, size_t max_faces, bool polylines = false)
      : max_vertices_(max_vertices),
        max_faces_(max_faces),
        polylines_(polylines) {}
  // `where` names the slice in errors ("message 3").
  Status Add(const v1::MeshChunk& chunk, const std::string& where);
  // The soup, its channels checked; indices are checked by the core.
  Status Finish(PolygonSoup* soup);
  size_t vertices() const { return soup_.vertices.size(); }
  size_t faces() const { return soup_.faces.size(); }
  int64_t attribute_bytes() const { return attribute_bytes_; }
  size_t channels() const { return soup_.attributes.size(); }
  size_t corners() const { return corners_; }

 private:
  Status AddAttribute(const v1::AttributeChunk& a, const std::string& where);

  static constexpr uint32_t kMaxPolygonCorners = 1000;
  static constexpr size_t kMaxChannels = 16, kMaxNameBytes = 64;
  size_t max_vertices_, max_faces_;
  bool polylines_;
  size_t corners_ = 0;
  int64_t attribute_bytes_ = 0;
  PolygonSoup soup_;
  std::vector<bool> per_corner_;  // per channel, as announced
};

}  // namespace dot::wire

#endif  // DOT_PROTO_SOUP_WIRE_H_
