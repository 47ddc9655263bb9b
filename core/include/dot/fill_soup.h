// SPDX-License-Identifier: AGPL-3.0-or-later
// The use case "fill the holes of the mesh a user sent": repair the polygon
// soup (or, with FillOptions::repair off, only triangulate its polygons),
// then FillHoles. The FillHoles RPC, `dotctl fill-holes --local` and the
// FillHoles fuzzer run this one function, so they answer alike.
#ifndef DOT_FILL_SOUP_H_
#define DOT_FILL_SOUP_H_

#include <cstdint>
#include <string>
#include <vector>

#include "dot/fill_holes.h"
#include "dot/io.h"
#include "dot/mesh_repair.h"

namespace dot {

struct SoupFillResult {
  // status: CheckFillOptions' or the repair's refusal, or FillHoles'
  // status; mesh and report as
  // FillHoles gives them (the mesh is the repaired one, then new vertices).
  FillResult fill;
  // What repair changed; with FillOptions::repair off its counts are zero
  // and vertex_map empty (ids unchanged), but face_origin is set.
  RepairReport repair;
  // The repaired mesh that was filled: the first input_vertices vertices
  // of fill.mesh are its vertices.
  int64_t input_vertices = 0, input_faces = 0;
  // When fill has a mesh and the soup had attribute channels, or polygons
  // and FillOptions::keep_polygons: that mesh (moved here, fill.mesh left
  // empty) with its channels carried; vertex ids as in fill.mesh. With
  // keep_polygons its faces are regrouped into the polygons sent; without,
  // they are fill.mesh's triangles, in order. Empty otherwise (a soup of
  // plain triangles is answered in fill.mesh alone).
  PolygonSoup soup;
  // What was not carried (an attribute channel dropped, and why).
  std::vector<std::string> notes;
};

// `soup` is taken by value and released once repaired: a caller that
// moves its soup in holds one copy of the mesh, not two. Options are
// checked (CheckFillOptions) before any work; selection.through_vertices
// are soup ids (mapped through the repair); `control`'s cancel and deadline
// hold in every step, and a stop after the holes were found keeps what
// was filled (FillResult::partial); `on_progress` as in FillHoles, from
// the repair on.
SoupFillResult FillSoup(PolygonSoup soup, const FillOptions& options = {},
                        const Control& control = {},
                        const FillProgressFn& on_progress = nullptr);

// A filled hole in the ids of the soup as it was sent, for a caller that
// keeps its mesh and adds only what is new (the FillHoles RPC's patches
// answer, Blender): new vertices are numbered on from the soup's, patch
// after patch (new_vertices[k] is vertex first_vertex + k); faces use soup
// vertex ids, a duplicate that repair merged named by its first copy; each
// soup face that edge protection split is listed with the triangles that
// replace all of it (a polygon's other triangles included), once: by the
// last patch that splits it, when two do. Faces agree with the repaired
// orientation (RepairReport::reoriented_faces says whether the soup's own
// faces were flipped). With attribute channels, each patch gives every
// channel's values at the corners of its faces and replacements.
struct PatchChannel {
  std::string name;
  int dims = 0;
  std::vector<float> faces;     // dims per corner of SentPatch::faces
  std::vector<float> replaced;  // of each replacement's triangles, in order
};
struct SentPatch {
  int32_t hole = 0;  // HoleReport::id
  int32_t first_vertex = 0;
  std::vector<Vec3> new_vertices;
  std::vector<Triangle> faces;
  std::vector<int32_t> replaced_faces;
  std::vector<std::vector<Triangle>> replacements;
  std::vector<PatchChannel> attributes;  // result.soup's channels, in order
};
// `soup_vertices`: how many vertices the soup had as sent. The fill must
// have run without FillOptions::keep_polygons (else, or when the result is
// not laid out as FillHoles promises, there are none).
std::vector<SentPatch> PatchesAsSent(const SoupFillResult& result,
                                     int64_t soup_vertices);

}  // namespace dot

#endif  // DOT_FILL_SOUP_H_
