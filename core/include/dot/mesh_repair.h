// SPDX-License-Identifier: AGPL-3.0-or-later
// The input repair users expect before hole filling, each step counted:
// vertices with identical coordinates merged, degenerate and duplicate faces
// dropped, polygons triangulated, faces oriented consistently per connected
// component (closed components outward). What cannot be repaired (an edge
// shared by more than two faces, a non-orientable component) is refused
// with a message naming it. Vertices where several fans of faces meet
// (non-manifold vertices) are counted and kept: the loops through them are
// split by FindHoleLoops, and duplicating them would leave coincident
// vertices that exact intersection tests rightly flag.
#ifndef DOT_MESH_REPAIR_H_
#define DOT_MESH_REPAIR_H_

#include <cstdint>
#include <string>
#include <vector>

#include "dot/control.h"
#include "dot/io.h"
#include "dot/problem.h"
#include "dot/status.h"

namespace dot {

struct RepairReport {
  int64_t merged_vertices = 0;        // duplicates of an earlier vertex
  int64_t degenerate_faces = 0;       // repeated corner or zero area
  int64_t duplicate_faces = 0;        // same corners as an earlier face
  int64_t triangulated_polygons = 0;  // faces with more than 3 corners
  int64_t reoriented_faces = 0;       // flipped to agree with neighbours
  int64_t non_manifold_vertices = 0;  // kept; their loops are split
  int64_t components = 0;
  // Old vertex index -> index in the repaired mesh.
  std::vector<int32_t> vertex_map;
  // Repaired triangle -> the index of the soup face it comes from.
  std::vector<int32_t> face_origin;

  bool changed() const {
    return merged_vertices + degenerate_faces + duplicate_faces +
               reoriented_faces >
           0;
  }
  std::string Summary() const;  // one line, e.g. for a CLI
};

// Repairs `soup` into `out`. Vertices keep their first-occurrence order.
// kInvalidArgument when nothing is left (every face degenerate or
// duplicate). `control`'s cancel and deadline are honoured in every step.
Status RepairMesh(const PolygonSoup& soup, MeshData* out, RepairReport* report);
Status RepairMesh(const PolygonSoup& soup, const Control& control,
                  MeshData* out, RepairReport* report);
// The same, releasing the soup as soon as its faces are read (before the
// repair's largest step): a caller that moves its soup in holds the mesh
// about once. `soup` is left empty.
Status RepairMesh(PolygonSoup&& soup, const Control& control, MeshData* out,
                  RepairReport* report);

}  // namespace dot

#endif  // DOT_MESH_REPAIR_H_
