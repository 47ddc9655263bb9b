// SPDX-License-Identifier: AGPL-3.0-or-later
// The filled mesh given back in the shape it was sent (FillOptions::
// keep_polygons): polygons the fill did not split kept whole, every
// attribute channel carried through the repair and interpolated into the
// new corners.
//
// How new corners get their values:
//  - pieces of a face that edge protection split lie in that face: their
//    new corners are interpolated linearly (barycentric) in it;
//  - a patch's interior is harmonic (mean-value weights: positive, and
//    exact for a linear field on a flat patch) with its rim
//    fixed to the values of the faces across the rim, so it blends smoothly
//    from the hole's border. Where the rim crosses a seam (a rim vertex
//    whose faces on either side disagree), the rim is cut into arcs of
//    agreeing values; each arc's field is solved with only that arc fixed,
//    each patch face takes the field of the arc nearest to it, and the seam
//    runs on through the patch where neighbouring faces took different arcs.
//  - a "normal" channel's new entries are the patch's own vertex normals
//    (area-weighted, turned to agree with the rim's), as a renderer would
//    compute them: a blend of the rim's would not follow the new surface.
//    Barycentric "normal" entries are renormalized. Every other value is
//    a blend with positive weights, so it stays within the range of the
//    values it comes from (colours on a 0..255 scale stay on it).
#ifndef DOT_CORE_FILL_SOUP_OUTPUT_H_
#define DOT_CORE_FILL_SOUP_OUTPUT_H_

#include <cstdint>
#include <string>
#include <vector>

#include "dot/fill_holes.h"
#include "dot/mesh.h"
#include "dot/mesh_repair.h"
#include "dot/status.h"

namespace dot {

// What of the soup as sent outlives its repair: the channels' values and,
// per repaired triangle corner, the entry each channel gives it; the
// repaired triangles (a split face's corners, for its pieces).
struct SoupTrace {
  std::vector<AttributeChannel> channels;  // indices: 3 per triangle
  std::vector<bool> per_vertex;            // per channel: as sent
  std::vector<Triangle> triangles;
  // Repaired vertex -> a soup vertex merged into it: the entry of a vertex
  // on no face, for the channels sent per vertex.
  std::vector<int32_t> sent_vertex;
};

// `faces` as sent, `channels` their attributes (moved in), `repair` and
// `repaired` as RepairMesh or TriangulateSoup left them.
SoupTrace TraceSoup(const FaceList& faces,
                    std::vector<AttributeChannel> channels,
                    const RepairReport& repair, const MeshData& repaired);

// `fill`'s mesh (moved out) as a soup: with `regroup`, the first
// `input_faces` triangles regrouped into the polygons they were cut from
// (by `face_origin`) unless a patch split one, then the new triangles;
// without, fill.mesh's triangles one face each, in their order. The
// trace's channels on its corners, kept per vertex where no vertex has
// corners that disagree. `notes` receives what could not be carried.
PolygonSoup SoupOfFill(FillResult* fill,
                       const std::vector<int32_t>& face_origin,
                       int64_t input_faces, SoupTrace trace, bool regroup,
                       std::vector<std::string>* notes);

}  // namespace dot

#endif  // DOT_CORE_FILL_SOUP_OUTPUT_H_
