// SPDX-License-Identifier: AGPL-3.0-or-later
#include "solve/prepared_space.h"

namespace dot {
namespace {

template <typename T>
void AppendBytes(const T& value, std::string* out) {
  out->append(reinterpret_cast<const char*>(&value), sizeof(value));
}

template <typename V>
int64_t CapacityBytes(const V& v) {
  return static_cast<int64_t>(v.capacity() * sizeof(v[0]));
}

}  // namespace

int64_t PreparedSpace::Bytes() const {
  return static_cast<int64_t>(sizeof(*this)) + CapacityBytes(loop.vertices) +
         CapacityBytes(loop.normals) + CapacityBytes(loop.edge_normals) +
         CapacityBytes(loop.ids) + CapacityBytes(triangles) +
         adjacency.Bytes() + CapacityBytes(unit_normals);
}

std::string SpaceCacheKey(const Problem& problem, const Options& options) {
  std::string key;
  key.reserve(
      sizeof(Vec3) * (problem.vertices.size() + problem.normals.size()) + 64);
  AppendBytes(problem.vertices.size(), &key);
  AppendBytes(problem.normals.size(), &key);
  AppendBytes(options.space, &key);
  AppendBytes(options.delaunay, &key);
  AppendBytes(options.protect_edges, &key);
  AppendBytes(options.max_inserted_vertices, &key);
  AppendBytes(options.planar_tolerance, &key);
  key.append(reinterpret_cast<const char*>(problem.vertices.data()),
             sizeof(Vec3) * problem.vertices.size());
  key.append(reinterpret_cast<const char*>(problem.normals.data()),
             sizeof(Vec3) * problem.normals.size());
  // Not weight-like: the cached loop carries the edge normals, and the
  // forbidden chords shape the candidates.
  AppendBytes(problem.edge_face_normals.size(), &key);
  key.append(reinterpret_cast<const char*>(problem.edge_face_normals.data()),
             sizeof(Vec3) * problem.edge_face_normals.size());
  AppendBytes(problem.forbidden_edges.size(), &key);
  for (const auto& [a, b] : problem.forbidden_edges) {
    AppendBytes(a, &key);
    AppendBytes(b, &key);
  }
  return key;
}

}  // namespace dot
