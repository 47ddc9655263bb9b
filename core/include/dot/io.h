// SPDX-License-Identifier: AGPL-3.0-or-later
// Reading polygons and writing meshes.
//
// Polygon files:
//  - plain text: one vertex per line, "x y z" or "x y z nx ny nz" (a boundary
//    normal); blank lines and lines starting with '#' are skipped.
//  - OBJ: "v x y z" vertices and an "l i j k ..." polyline giving the loop
//    (1-based, negative indices count from the end; a repeated first index
//    closing the loop is dropped). Several "l" lines (one per edge, "l a b",
//    as Blender writes a loop) are chained into the loop, which starts with
//    the first edge in its direction; edges that do not form exactly one
//    closed loop (an open chain, a branch, several loops) are refused with a
//    message naming a vertex. Without an "l" line, the "v" order is the loop.
//    "vn" lines, one per vertex, are boundary normals.
// Either way, a loop that ends by repeating its first point (the same
// coordinates, as many exporters close a loop) has the repeats dropped, and a
// note saying so is added to `notes` when given.
// Mesh files (by extension): written as .obj, .off or .ply (binary little
// endian float64 by default, ASCII on request), every coordinate exactly
// (17 significant digits in text), or .stl (binary by default: float32, so
// coordinates are rounded to single precision; ASCII writes every digit,
// though STL readers, CGAL's included, read single precision); read with CGAL's
// polygon-soup reader from .stl (ASCII or binary), CGAL's OFF scanner for
// .off, and our own readers for .obj and .ply (ASCII or binary, either byte
// order; they carry attributes, mesh_io/mesh_formats.h), polygons
// triangulated.
#ifndef DOT_IO_H_
#define DOT_IO_H_

#include <iosfwd>
#include <string>
#include <vector>

#include "dot/geometry.h"
#include "dot/mesh.h"
#include "dot/status.h"

namespace dot {

// Format from the extension: .obj is OBJ, anything else plain text. Errors
// name the file (and the reason a file cannot be opened). `notes`, when not
// null, receives what the reader changed (a dropped closing vertex).
// Several loops (PolygonData::loop_sizes): in text, blocks of lines
// separated by blank lines; in OBJ, 'l' lines that close into several loops
// (in the order their first edges appear). The text writer separates loops
// the same way.
Status ReadPolygonFile(const std::string& path, PolygonData* out,
                       std::vector<std::string>* notes = nullptr);
Status ReadPolygonText(std::istream& in, PolygonData* out,
                       std::vector<std::string>* notes = nullptr);
Status ReadPolygonObj(std::istream& in, PolygonData* out,
                      std::vector<std::string>* notes = nullptr);
Status WritePolygonText(const std::string& path, const PolygonData& polygon);
Status WritePolygonText(std::ostream& out, const PolygonData& polygon);

// Format from the extension: .obj, .ply, .off or .stl.
Status WriteMeshFile(const std::string& path, const MeshData& mesh,
                     bool ascii = false);
Status WriteMesh(std::ostream& out, const std::string& format,
                 const MeshData& mesh, bool ascii = false);

// A mesh as read: faces of any size, nothing merged or dropped.
// Format from the extension (.off, .obj, .ply, .stl); kInvalidArgument names
// the file and what is wrong with it.
// Attributes (normals, colours, UVs) are read from OBJ and PLY into the
// soup's channels (see PolygonSoup); what a file has that is not kept
// (materials, per-face colours, other elements) is named in `notes`.
Status ReadPolygonSoupFile(const std::string& path, PolygonSoup* out,
                           std::vector<std::string>* notes = nullptr);
// kInvalidArgument naming the first attribute channel that does not fit
// the soup (dims outside 1..16, a value count that is not whole entries, a
// non-finite value, an entry count other than the vertex count, corner
// indices that do not match the faces or name no entry).
Status CheckAttributes(const PolygonSoup& soup);
// A soup with its polygons and attribute channels, format from the
// extension (.obj, .ply, .off, .stl; OFF and STL keep no attributes, and
// STL no polygons): a channel a format cannot hold is named in `notes`.
Status WriteSoup(std::ostream& out, const std::string& format,
                 const PolygonSoup& soup, bool ascii = false,
                 std::vector<std::string>* notes = nullptr);
Status WriteSoupFile(const std::string& path, const PolygonSoup& soup,
                     bool ascii = false,
                     std::vector<std::string>* notes = nullptr);
// A triangle mesh: ReadPolygonSoupFile, then polygons with more than three
// corners triangulated (DOT with the area metric over their planar CDT; a
// fan where that fails). No repair: see dot/mesh_repair.h.
Status ReadMeshFile(const std::string& path, MeshData* out);
// Triangulates the faces of a soup as ReadMeshFile does. `control`'s cancel
// and deadline are honoured between and within polygons.
struct Control;
Status TriangulateSoup(const PolygonSoup& soup, MeshData* out);
// `face_of`, when given, receives for each triangle the soup face it
// comes from.
Status TriangulateSoup(const PolygonSoup& soup, const Control& control,
                       MeshData* out, std::vector<int32_t>* face_of = nullptr);

}  // namespace dot

#endif  // DOT_IO_H_
