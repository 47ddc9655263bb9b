// SPDX-License-Identifier: AGPL-3.0-or-later
// The steps of SurfaceNetwork, one patch (or the whole network) at a time.
// A patch's faces name graph vertices, and ids >= first_new for its own new
// vertices (new_vertices[id - first_new]); the network step renumbers them.
#ifndef DOT_CORE_NETWORK_SURFACE_STEPS_H_
#define DOT_CORE_NETWORK_SURFACE_STEPS_H_

#include <string>
#include <utility>
#include <vector>

#include "dot/network.h"

namespace dot {

struct PatchMesh {
  std::vector<Vec3> new_vertices;
  std::vector<Triangle> faces;
  // A seam patch (a loop that runs a path of curves both ways, split in two
  // pieces): the piece of each face, 0 or 1, which refinement keeps apart
  // (the seam and the new path stay borders). Empty otherwise.
  std::vector<char> piece;
};

// DOT over the cycle's loops (ids into `vertices`, patch orientation), with
// `normals` (per vertex, empty: none) as boundary normals and
// `forbidden` chords (graph vertex pairs) never used: Delaunay first, then
// every triangle with the Delaunay ones first for one loop, then (a short
// loop) bending alone over every triangle, which adds kBendingAloneNote to
// the report's reason (and a solve without it takes the note out). Fills
// the report's space, solver, cost and triangulate_ms; kNoTriangulation
// says why no step found one.
inline constexpr char kBendingAloneNote[] =
    "the optimum of bending alone over every triangle (the weights' "
    "surfaces cross themselves)";
Status TriangulatePatch(
    const std::vector<Vec3>& vertices,
    const std::vector<std::vector<int32_t>>& loops,
    const std::vector<Vec3>& normals,
    const std::vector<std::pair<int32_t, int32_t>>& forbidden,
    const SurfaceOptions& options, const Control& control, PatchMesh* patch,
    PatchReport* report);

// The last resort for one loop no DOT step triangulated without meeting
// the rest: a fan of triangles from a new vertex (id `centre`, the one
// new_vertices holds) at the loop's centroid (refinement and fairing then shape
// it). kNoTriangulation for several loops.
Status FanPatch(const std::vector<Vec3>& vertices,
                const std::vector<std::vector<int32_t>>& loops, int32_t centre,
                PatchMesh* patch);

// Liepa refinement of one patch alone, its boundary (the curves) kept:
// new vertices inside only, so neighbours still meet on the curves (a seam
// patch piece by piece). Past
// `cap` new vertices the patch stays unrefined (its reason says so).
Status RefinePatch(const NetworkGraph& graph, const SurfaceOptions& options,
                   const Control& control, int32_t first_new, size_t cap,
                   PatchMesh* patch, PatchReport* report);

// Fairs the free vertices of `mesh` (ids >= first_free, those refinement
// added) in one system over the whole mesh, every other vertex fixed, and
// `fixed` (ids >= first_free) fixed too. Returns kOk with *faired false
// when the mesh is not a manifold surface or the system could not be
// solved (`why` says which), or with no vertex free to move (`why` left
// empty); a stop (cancel, deadline) as not OK.
Status FairMesh(MeshData* mesh, int32_t first_free,
                const std::vector<char>& fixed, int continuity,
                const Control& control, bool* faired, std::string* why);

}  // namespace dot

#endif  // DOT_CORE_NETWORK_SURFACE_STEPS_H_
