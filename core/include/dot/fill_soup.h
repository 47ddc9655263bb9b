// SPDX-License-Identifier: AGPL-3.0-or-later
// The use case "fill the holes of the mesh a user sent": repair the polygon
// soup (or, with FillOptions::repair off, only triangulate its polygons),
// then FillHoles. The FillHoles RPC, `dotctl fill-holes --local` and the
// FillHoles fuzzer run this one function, so they answer alike.
#ifndef DOT_FILL_SOUP_H_
#define DOT_FILL_SOUP_H_

#include <cstdint>

#include "dot/fill_holes.h"
#include "dot/io.h"
#include "dot/mesh_repair.h"

namespace dot {

struct SoupFillResult {
  // status: CheckFillOptions' or the repair's refusal, or FillHoles'
  // status; mesh and report as
  // FillHoles gives them (the mesh is the repaired one, then new vertices).
  FillResult fill;
  RepairReport repair;  // all zero when FillOptions::repair is off
  // The repaired mesh that was filled: the first input_vertices vertices
  // of fill.mesh are its vertices.
  int64_t input_vertices = 0, input_faces = 0;
};

// `soup` is taken by value and released once repaired: a caller that
// moves its soup in holds one copy of the mesh, not two. Options are
// checked (CheckFillOptions) before any work; `control`'s cancel and
// deadline hold in every step; `on_hole` as in FillHoles.
SoupFillResult FillSoup(PolygonSoup soup, const FillOptions& options = {},
                        const Control& control = {},
                        const HoleProgressFn& on_hole = nullptr);

}  // namespace dot

#endif  // DOT_FILL_SOUP_H_
