// SPDX-License-Identifier: AGPL-3.0-or-later
// The polygon as the solvers see it: vertex ids in loop order over a vertex
// array that edge protection may append to. Several loops are concatenated
// (positions of loop 0 first), with their sizes.
#ifndef DOT_CORE_POLYGON_POLYGON_LOOP_H_
#define DOT_CORE_POLYGON_POLYGON_LOOP_H_

#include <cstdint>
#include <vector>

#include "dot/geometry.h"

namespace dot {

struct PolygonLoop {
  std::vector<Vec3> vertices;  // input vertices, then inserted ones
  std::vector<Vec3> normals;   // parallel to vertices, or empty
  // Parallel to vertices, or empty: the normal of the surface face across
  // the loop edge that starts at the vertex (Problem::edge_face_normals).
  std::vector<Vec3> edge_normals;
  std::vector<int32_t> ids;    // the loop: position -> vertex id
  std::vector<int32_t> sizes;  // several loops: their sizes; empty: one

  int32_t size() const { return static_cast<int32_t>(ids.size()); }
  int32_t LoopCount() const {
    return sizes.empty() ? 1 : static_cast<int32_t>(sizes.size());
  }
  // Position -> the next position along its loop.
  std::vector<int32_t> Successors() const {
    std::vector<int32_t> next(ids.size());
    int32_t begin = 0;
    for (int32_t l = 0; l < LoopCount(); ++l) {
      const int32_t n = sizes.empty() ? size() : sizes[l];
      for (int32_t i = 0; i < n; ++i) next[begin + i] = begin + (i + 1) % n;
      begin += n;
    }
    return next;
  }
  std::vector<Vec3> Points() const {
    std::vector<Vec3> p;
    p.reserve(ids.size());
    for (int32_t id : ids) p.push_back(vertices[id]);
    return p;
  }
  // edge_normals in loop order (position i: the edge i -> i+1), or empty.
  std::vector<Vec3> EdgeNormalsByPosition() const {
    std::vector<Vec3> p;
    if (edge_normals.empty()) return p;
    p.reserve(ids.size());
    for (int32_t id : ids) p.push_back(edge_normals[id]);
    return p;
  }
};

}  // namespace dot

#endif  // DOT_CORE_POLYGON_POLYGON_LOOP_H_
