// SPDX-License-Identifier: AGPL-3.0-or-later
// What hole filling asks of a mesh, indexed once: the faces around each
// vertex (compressed rows; a vertex's neighbours are their corners) and the
// faces in a box tree (which faces come near a patch).
#ifndef DOT_CORE_MESH_TOPOLOGY_H_
#define DOT_CORE_MESH_TOPOLOGY_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "dot/mesh.h"
#include "mesh/face_tree.h"

namespace dot {

struct MeshTopology {
  std::vector<int32_t> face_begin, faces;  // vertex v: faces[face_begin[v]..]
  std::shared_ptr<const FaceTree> face_tree;  // null: BuildMeshAdjacency
};

// The rows only, without the face tree.
std::shared_ptr<const MeshTopology> BuildMeshAdjacency(const MeshData& mesh);
// The rows and the face tree, built side by side; `mesh` must outlive the
// result. Also declared in dot/fill_holes.h, whose per-hole stages take it.
std::shared_ptr<const MeshTopology> BuildMeshTopology(const MeshData& mesh);

}  // namespace dot

#endif  // DOT_CORE_MESH_TOPOLOGY_H_
