// SPDX-License-Identifier: AGPL-3.0-or-later
#include "wire/soup_wire.h"

#include <algorithm>
#include <vector>

namespace dot::wire {

SoupChunkWriter::SoupChunkWriter(const PolygonSoup& soup, size_t max_bytes)
    : soup_(&soup), max_bytes_(std::max<size_t>(64, max_bytes)) {
  for (FaceView f : soup.faces) all_triangles_ &= f.size() == 3;
}

bool SoupChunkWriter::Next(v1::MeshChunk* chunk) {
  chunk->Clear();
  const PolygonSoup& soup = *soup_;
  if (next_vertex_ < soup.vertices.size()) {
    const size_t end =
        std::min(soup.vertices.size(), next_vertex_ + max_bytes_ / 24);
    chunk->set_first_vertex(static_cast<uint32_t>(next_vertex_));
    chunk->mutable_vertices()->Reserve(
        static_cast<int>(3 * (end - next_vertex_)));
    for (; next_vertex_ < end; ++next_vertex_) {
      const Vec3& p = soup.vertices[next_vertex_];
      chunk->add_vertices(p.x);
      chunk->add_vertices(p.y);
      chunk->add_vertices(p.z);
    }
    return true;
  }
  chunk->set_first_vertex(static_cast<uint32_t>(soup.vertices.size()));
  if (next_face_ < soup.faces.size()) {
    chunk->set_first_triangle(static_cast<uint32_t>(next_face_));
    const size_t indices_per = std::max<size_t>(3, max_bytes_ / 5);
    size_t indices = 0;
    for (; next_face_ < soup.faces.size(); ++next_face_) {
      const FaceView f = soup.faces[next_face_];
      if (indices > 0 && indices + f.size() > indices_per) break;
      for (int32_t v : f) chunk->add_triangles(static_cast<uint32_t>(v));
      if (!all_triangles_) {
        chunk->add_face_sizes(static_cast<uint32_t>(f.size()));
      }
      indices += f.size();
    }
    return true;
  }
  chunk->set_first_triangle(static_cast<uint32_t>(soup.faces.size()));
  if (channel_ >= soup.attributes.size()) return false;
  const AttributeChannel& ch = soup.attributes[channel_];
  v1::AttributeChunk* a = chunk->mutable_attribute();
  a->set_name(ch.name);
  a->set_dims(static_cast<uint32_t>(ch.dims));
  a->set_per_corner(ch.per_corner());
  const size_t entries = ch.entries();
  if (next_value_ < entries) {
    const size_t per = std::max<size_t>(1, max_bytes_ / (5 * ch.dims));
    const size_t end = std::min(entries, next_value_ + per);
    a->set_first_value(static_cast<uint32_t>(next_value_));
    a->mutable_values()->Add(ch.entry(next_value_), ch.entry(end));
    next_value_ = end;
  } else {
    a->set_first_value(static_cast<uint32_t>(entries));
    const size_t end =
        std::min(ch.indices.size(), next_index_ + max_bytes_ / 5);
    a->set_first_corner(static_cast<uint32_t>(next_index_));
    for (; next_index_ < end; ++next_index_) {
      a->add_indices(static_cast<uint32_t>(ch.indices[next_index_]));
    }
  }
  // A channel with no values (no vertices) still goes, in one slice.
  if (next_value_ >= entries && next_index_ >= ch.indices.size()) {
    ++channel_;
    next_value_ = next_index_ = 0;
  }
  return true;
}

Status SoupChunkReader::Add(const v1::MeshChunk& c, const std::string& where) {
  if (c.vertices_size() % 3 != 0) {
    return InvalidArgument(where + " has " + std::to_string(c.vertices_size()) +
                           " coordinates, not a multiple of 3");
  }
  const bool has_faces = !c.triangles().empty();
  if ((!c.vertices().empty() || has_faces) && !soup_.attributes.empty()) {
    return InvalidArgument(where + " sends " +
                           (has_faces ? "faces" : "vertices") +
                           " after attributes");
  }
  if (!c.vertices().empty() && !soup_.faces.empty()) {
    return InvalidArgument(where + " sends vertices after faces");
  }
  if (!c.vertices().empty() && c.first_vertex() != soup_.vertices.size()) {
    return InvalidArgument(
        where + " starts at vertex " + std::to_string(c.first_vertex()) +
        " but " + std::to_string(soup_.vertices.size()) +
        " vertices have arrived (slices come in order, first_vertex set)");
  }
  if (has_faces && c.first_triangle() != soup_.faces.size()) {
    return InvalidArgument(
        where + " starts at face " + std::to_string(c.first_triangle()) +
        " but " + std::to_string(soup_.faces.size()) +
        " faces have arrived (slices come in order, first_triangle set)");
  }
  if (soup_.vertices.size() + c.vertices_size() / 3 > max_vertices_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh has more than " +
                          std::to_string(max_vertices_) +
                          " vertices, the server's limit");
  }
  for (int i = 0; i < c.vertices_size(); i += 3) {
    soup_.vertices.push_back(
        {c.vertices(i), c.vertices(i + 1), c.vertices(i + 2)});
  }
  if (c.face_sizes().empty()) {
    if (c.triangles_size() % 3 != 0) {
      return InvalidArgument(where + " has " +
                             std::to_string(c.triangles_size()) +
                             " face indices, not a multiple of 3 (give "
                             "face_sizes for polygons)");
    }
  } else {
    size_t total = 0;
    const uint32_t least = polylines_ ? 2 : 3;
    for (uint32_t k : c.face_sizes()) {
      if (k < least) {
        return InvalidArgument(
            where + (polylines_ ? " has a polyline of " : " has a face of ") +
            std::to_string(k) +
            (polylines_ ? " points; a polyline needs at least 2"
                        : " corners; a face needs at least 3"));
      }
      if (!polylines_ && k > kMaxPolygonCorners) {
        return InvalidArgument(where + " has a face of " + std::to_string(k) +
                               " corners; at most " +
                               std::to_string(kMaxPolygonCorners) +
                               " are accepted");
      }
      total += k;
    }
    if (total != static_cast<size_t>(c.triangles_size())) {
      return InvalidArgument(
          where + ": face_sizes add up to " + std::to_string(total) + " but " +
          std::to_string(c.triangles_size()) + " face indices were sent");
    }
  }
  const size_t faces = c.face_sizes().empty()
                           ? static_cast<size_t>(c.triangles_size()) / 3
                           : static_cast<size_t>(c.face_sizes_size());
  if (soup_.faces.size() + faces > max_faces_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh has more than " + std::to_string(max_faces_) +
                          " faces, the server's limit");
  }
  // Corners, not faces, are what polygons cost (each is triangulated).
  corners_ += static_cast<size_t>(c.triangles_size());
  if (corners_ > 3 * max_faces_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh's faces have more than " +
                          std::to_string(3 * max_faces_) +
                          " corners in all, the server's limit");
  }
  int next = 0;
  std::vector<int32_t> face;
  for (size_t f = 0; f < faces; ++f) {
    const int k =
        c.face_sizes().empty() ? 3 : static_cast<int>(c.face_sizes(f));
    face.clear();
    for (int corner = 0; corner < k; ++corner) {
      const uint32_t v = c.triangles(next++);
      if (v >= soup_.vertices.size()) {
        return InvalidArgument(
            (polylines_ ? "polyline " : "face ") +
            std::to_string(soup_.faces.size()) + " has vertex index " +
            std::to_string(v) + ", but only " +
            std::to_string(soup_.vertices.size()) + " vertices were sent");
      }
      face.push_back(static_cast<int32_t>(v));
    }
    soup_.faces.push_back(face);
  }
  if (c.has_attribute()) return AddAttribute(c.attribute(), where);
  return OkStatus();
}

Status SoupChunkReader::AddAttribute(const v1::AttributeChunk& a,
                                     const std::string& where) {
  const std::string name = "attribute '" + a.name() + "'";
  if (a.name().empty() || a.name().size() > kMaxNameBytes) {
    return InvalidArgument(where + ": an attribute needs a name of 1 to " +
                           std::to_string(kMaxNameBytes) + " bytes");
  }
  if (soup_.faces.empty()) {
    return InvalidArgument(where + " sends " + name + " before any face");
  }
  const bool starts =
      soup_.attributes.empty() || soup_.attributes.back().name != a.name();
  if (starts) {
    for (const AttributeChannel& ch : soup_.attributes) {
      if (ch.name == a.name()) {
        return InvalidArgument(where + ": " + name +
                               " is sent twice (a channel's slices come "
                               "one after another)");
      }
    }
    if (soup_.attributes.size() >= kMaxChannels) {
      return InvalidArgument(where + ": more than " +
                             std::to_string(kMaxChannels) +
                             " attribute channels");
    }
    if (a.dims() < 1 || a.dims() > 16) {
      return InvalidArgument(where + ": " + name + " has " +
                             std::to_string(a.dims()) +
                             " values an entry; 1 to 16 are allowed");
    }
    AttributeChannel& ch = soup_.attributes.emplace_back();
    ch.name = a.name();
    ch.dims = static_cast<int>(a.dims());
    per_corner_.push_back(a.per_corner());
  }
  AttributeChannel& ch = soup_.attributes.back();
  if (!starts && a.first_value() == 0 && !a.values().empty() &&
      ch.entries() > 0) {
    return InvalidArgument(where + ": " + name +
                           " is sent twice (a channel's slices come "
                           "one after another)");
  }
  if (a.dims() != static_cast<uint32_t>(ch.dims) ||
      a.per_corner() != per_corner_.back()) {
    return InvalidArgument(where + ": " + name +
                           " changes its dims or per_corner between slices");
  }
  if (a.values_size() % ch.dims != 0) {
    return InvalidArgument(
        where + ": " + name + " has " + std::to_string(a.values_size()) +
        " values, not whole entries of " + std::to_string(ch.dims));
  }
  if (!a.values().empty() && !ch.indices.empty()) {
    return InvalidArgument(where + ": " + name +
                           " sends values after its indices");
  }
  if (!a.values().empty() && a.first_value() != ch.entries()) {
    return InvalidArgument(where + ": " + name + " starts at entry " +
                           std::to_string(a.first_value()) + " but " +
                           std::to_string(ch.entries()) + " have arrived");
  }
  if (!a.indices().empty() && a.first_corner() != ch.indices.size()) {
    return InvalidArgument(where + ": " + name + " starts at corner " +
                           std::to_string(a.first_corner()) + " but " +
                           std::to_string(ch.indices.size()) + " have arrived");
  }
  if (!a.per_corner() && !a.indices().empty()) {
    return InvalidArgument(where + ": " + name +
                           " has corner indices but is not per_corner");
  }
  // Per vertex: an entry per vertex; per corner: never more entries or
  // indices than corners, so a channel costs at most what its mesh does.
  const size_t limit = a.per_corner() ? soup_.faces.corners() : vertices();
  const size_t entries = ch.entries() + a.values_size() / ch.dims;
  if (entries > limit ||
      ch.indices.size() + a.indices_size() > soup_.faces.corners()) {
    return InvalidArgument(where + ": " + name + " has more " +
                           (entries > limit ? "entries" : "indices") +
                           " than the mesh has " +
                           (a.per_corner() ? "face corners" : "vertices"));
  }
  ch.values.insert(ch.values.end(), a.values().begin(), a.values().end());
  for (uint32_t e : a.indices()) {
    ch.indices.push_back(
        static_cast<int32_t>(std::min<uint32_t>(e, INT32_MAX)));
  }
  attribute_bytes_ += 4 * (a.values_size() + a.indices_size());
  return OkStatus();
}

Status SoupChunkReader::Finish(PolygonSoup* soup) {
  for (size_t v = 0; v < soup_.vertices.size(); ++v) {
    if (!IsFinite(soup_.vertices[v])) {
      return InvalidArgument("vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
    }
  }
  for (size_t c = 0; c < per_corner_.size(); ++c) {
    const AttributeChannel& ch = soup_.attributes[c];
    if (per_corner_[c] && ch.indices.size() != soup_.faces.corners()) {
      return InvalidArgument(
          "attribute '" + ch.name + "' is per_corner but " +
          std::to_string(ch.indices.size()) + " indices arrived for " +
          std::to_string(soup_.faces.corners()) + " face corners");
    }
  }
  const Status s = CheckAttributes(soup_);
  if (!s.ok()) return s;
  *soup = std::move(soup_);
  return OkStatus();
}

}  // namespace dot::wire
