// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/fill_soup.h"

#include <utility>

namespace dot {

SoupFillResult FillSoup(PolygonSoup soup, const FillOptions& options,
                        const Control& control, const HoleProgressFn& on_hole) {
  SoupFillResult out;
  out.fill.status = CheckFillOptions(options);
  if (!out.fill.status.ok()) return out;
  MeshData mesh;
  out.fill.status = options.repair
                        ? RepairMesh(soup, control, &mesh, &out.repair)
                        : TriangulateSoup(soup, control, &mesh);
  soup = {};  // the repaired mesh replaces it
  if (!out.fill.status.ok()) return out;
  out.input_vertices = static_cast<int64_t>(mesh.vertices.size());
  out.input_faces = static_cast<int64_t>(mesh.triangles.size());
  out.fill = FillHoles(mesh, options, control, on_hole);
  return out;
}

}  // namespace dot
