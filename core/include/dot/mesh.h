// SPDX-License-Identifier: AGPL-3.0-or-later
// The plain data the readers fill and the algorithms take: a polygon with
// optional boundary normals, a triangle mesh, and a polygon soup (faces of
// any corner count, as files hold them).
#ifndef DOT_MESH_H_
#define DOT_MESH_H_

#include <cstdint>
#include <vector>

#include "dot/geometry.h"

namespace dot {

struct PolygonData {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;  // empty or one per vertex
};

struct MeshData {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

struct PolygonSoup {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int32_t>> faces;
};

// `mesh` as a soup of its triangles (what FillSoup and the wire take).
inline PolygonSoup ToSoup(const MeshData& mesh) {
  PolygonSoup soup{mesh.vertices, {}};
  soup.faces.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    soup.faces.push_back({t[0], t[1], t[2]});
  }
  return soup;
}

}  // namespace dot

#endif  // DOT_MESH_H_
