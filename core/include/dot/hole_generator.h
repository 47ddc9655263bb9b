// SPDX-License-Identifier: AGPL-3.0-or-later
// Test and benchmark data: hole boundaries cut into triangle meshes as in the
// paper (section 5.1). A disk-shaped hole grows from a random triangle, one
// incident triangle at a time, keeping its boundary a simple loop. This
// makes holes; it does not fill them (Triangulate does).
#ifndef DOT_HOLE_GENERATOR_H_
#define DOT_HOLE_GENERATOR_H_

#include <cstdint>
#include <vector>

#include "dot/io.h"
#include "dot/status.h"

namespace dot {

struct Hole {
  PolygonData boundary;  // loop of mesh vertices, with mesh vertex normals
  int triangles = 0;     // triangles removed
  std::vector<int32_t> removed;  // their indices in the mesh, ascending
};

// Grows a hole of `triangles` triangles from a triangle chosen by `seed`.
// Boundary normals are area-weighted normals of the triangles kept. Fails
// when the mesh has no room for such a hole around the seed. Edge protection
// is applied by Triangulate (Options::protect_edges).
Status GrowHole(const MeshData& mesh, int triangles, uint64_t seed, Hole* out);

// `mesh` restricted to the faces `keep` marks (one flag per triangle),
// vertices renumbered in order of first use, unused ones dropped.
MeshData SubMesh(const MeshData& mesh, const std::vector<bool>& keep);

// Test data for hole filling: `count` holes of `triangles` triangles each,
// grown from seeds derived from `seed`, apart from each other (no shared
// vertex). `holey` is the mesh without them (unused vertices dropped),
// `removed` the removed patches (the ground truth), each compacted.
// kInvalidArgument when the mesh has no room for that many holes.
Status CutHoles(const MeshData& mesh, int count, int triangles, uint64_t seed,
                MeshData* holey, MeshData* removed);

// CutHoles with an island in each hole: the first `island_triangles` its
// growth removed (a disk around its start) stay, apart from its rim, so
// each hole is a ring between two loops around a floating piece of
// surface (what a scan leaves). `removed` is the ring.
Status CutIslandHoles(const MeshData& mesh, int count, int triangles,
                      int island_triangles, uint64_t seed, MeshData* holey,
                      MeshData* removed);

}  // namespace dot

#endif  // DOT_HOLE_GENERATOR_H_
