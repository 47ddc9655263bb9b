// SPDX-License-Identifier: AGPL-3.0-or-later
// The mesh formats whose attributes dot carries, read and written by our
// own code: CGAL 5.5's polygon-soup readers give positions and faces only
// (its OBJ reader skips vt and vn, its PLY reader gives colours but neither
// normals nor texture coordinates), and a fill that keeps a scan's
// attributes needs them all.
//
// OBJ: "v x y z [r g b]", "vt u v [w]", "vn x y z", "f" with v, v/vt, v//vn
// or v/vt/vn corners (1-based; negative counts back from the end). Channels:
// "color" per vertex (when every v line has one), "uv" and "normal" per
// corner as the f lines index them. Lines of other kinds (o, g, s, usemtl,
// mtllib, l, p) are skipped; materials and groups are named in a note.
// PLY (ASCII, binary either byte order): vertex x, y, z (float or double);
// nx, ny, nz -> "normal"; red, green, blue[, alpha] -> "color" (integers
// scaled to [0, 1]); s, t / u, v / texture_u, texture_v -> "uv"; any other
// scalar vertex property -> a channel of its own name; face vertex_indices
// (or vertex_index) and texcoord (a list of 2 per corner) -> "uv" per
// corner. Other face properties and other elements are noted and skipped.
// Every count is bounded by the file's size before anything is allocated,
// and every error names the file and the line or item.
#ifndef DOT_CORE_MESH_IO_MESH_FORMATS_H_
#define DOT_CORE_MESH_IO_MESH_FORMATS_H_

#include <iosfwd>
#include <string>
#include <vector>

#include "dot/mesh.h"
#include "dot/status.h"

namespace dot {

Status ReadObjMesh(const std::string& path, PolygonSoup* out,
                   std::vector<std::string>* notes);
Status ReadPlyMesh(const std::string& path, PolygonSoup* out,
                   std::vector<std::string>* notes);

// Writers of a soup with its channels: OBJ writes "color" on v lines and
// "uv" / "normal" as vt / vn (indexed per corner when the channel is);
// PLY writes every channel as vertex properties, duplicating a vertex for
// each distinct combination of per-corner entries at it (a seam), and
// every coordinate as a double. A channel a format cannot hold is named in
// `notes`.
void WriteObjSoup(std::ostream& out, const PolygonSoup& soup,
                  std::vector<std::string>* notes);
void WritePlySoup(std::ostream& out, const PolygonSoup& soup, bool ascii,
                  std::vector<std::string>* notes);

}  // namespace dot

#endif  // DOT_CORE_MESH_IO_MESH_FORMATS_H_
