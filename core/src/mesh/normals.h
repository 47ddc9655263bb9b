// SPDX-License-Identifier: AGPL-3.0-or-later
// Face and vertex normals, in whatever coordinates the caller works in
// (`position(id)` gives a vertex's point: the mesh's own, or rescaled).
#ifndef DOT_CORE_MESH_NORMALS_H_
#define DOT_CORE_MESH_NORMALS_H_

#include <cstdint>

#include "dot/geometry.h"
#include "dot/mesh.h"
#include "mesh/topology.h"

namespace dot {

// The cross product of triangle t's edges: its normal, times twice its
// area.
template <class Position>
Vec3 FaceCross(const Triangle& t, const Position& position) {
  const Vec3 a = position(t[0]);
  return Cross(position(t[1]) - a, position(t[2]) - a);
}

// The area-weighted normal of vertex v: the sum of FaceCross over the
// faces around it, except those `skip(face)` names. Not normalized; zero
// when the faces cancel (a fold) or there are none.
template <class Position, class Skip>
Vec3 AreaWeightedNormal(const MeshData& mesh, const MeshTopology& topology,
                        int32_t v, const Position& position, const Skip& skip) {
  Vec3 sum;
  for (int32_t k = topology.face_begin[v]; k < topology.face_begin[v + 1];
       ++k) {
    const int32_t f = topology.faces[k];
    if (!skip(f)) sum = sum + FaceCross(mesh.triangles[f], position);
  }
  return sum;
}
template <class Position>
Vec3 AreaWeightedNormal(const MeshData& mesh, const MeshTopology& topology,
                        int32_t v, const Position& position) {
  return AreaWeightedNormal(mesh, topology, v, position,
                            [](int32_t) { return false; });
}

}  // namespace dot

#endif  // DOT_CORE_MESH_NORMALS_H_
