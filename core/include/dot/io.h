// SPDX-License-Identifier: AGPL-3.0-or-later
// Reading polygons and writing meshes.
//
// Polygon files:
//  - plain text: one vertex per line, "x y z" or "x y z nx ny nz" (a boundary
//    normal); blank lines and lines starting with '#' are skipped.
//  - OBJ: "v x y z" vertices and an "l i j k ..." polyline giving the loop
//    (1-based, negative indices count from the end; a repeated first index
//    closing the loop is dropped). Without an "l" line, the "v" order is the
//    loop. "vn" lines, one per vertex, are boundary normals.
// Mesh files (by extension): .obj, .ply (ASCII), .off.
#ifndef DOT_IO_H_
#define DOT_IO_H_

#include <iosfwd>
#include <string>
#include <vector>

#include "dot/geometry.h"
#include "dot/status.h"

namespace dot {

struct PolygonData {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;  // empty or one per vertex
};

struct MeshData {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

// Format from the extension: .obj is OBJ, anything else plain text.
Status ReadPolygonFile(const std::string& path, PolygonData* out);
Status ReadPolygonText(std::istream& in, PolygonData* out);
Status ReadPolygonObj(std::istream& in, PolygonData* out);
Status WritePolygonText(const std::string& path, const PolygonData& polygon);

// Format from the extension: .obj, .ply or .off.
Status WriteMeshFile(const std::string& path, const MeshData& mesh);
Status WriteMesh(std::ostream& out, const std::string& format,
                 const MeshData& mesh);
// Reads a triangle mesh from .off or .obj (polygons are fan-triangulated).
Status ReadMeshFile(const std::string& path, MeshData* out);

}  // namespace dot

#endif  // DOT_IO_H_
