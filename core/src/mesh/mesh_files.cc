// SPDX-License-Identifier: AGPL-3.0-or-later
// Mesh readers: CGAL's polygon-soup I/O (OFF, OBJ, PLY, STL; ASCII and
// binary), a well-kept library rather than four parsers of our own.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "dot/io.h"
#include "dot/triangulate.h"

namespace dot {
namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

std::string LowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// A polygon's triangles: DOT's minimal-area triangulation of its corners
// (planar polygons go through the 2D constrained Delaunay triangulation),
// or a fan when DOT refuses it (e.g. a polygon that repeats a corner).
void TriangulatePolygon(const PolygonSoup& soup, const std::vector<int32_t>& f,
                        std::vector<Triangle>* out) {
  if (f.size() > 3) {
    Problem p;
    for (int32_t v : f) p.vertices.push_back(soup.vertices[v]);
    const Result r = Triangulate(p);
    if (r.status.ok() && r.inserted.empty()) {
      for (const Triangle& t : r.triangles) {
        out->push_back({f[t[0]], f[t[1]], f[t[2]]});
      }
      return;
    }
  }
  for (size_t k = 1; k + 1 < f.size(); ++k) {
    out->push_back({f[0], f[k], f[k + 1]});
  }
}

}  // namespace

Status ReadPolygonSoupFile(const std::string& path, PolygonSoup* out) {
  *out = {};
  const std::string ext = LowerExtension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") {
    return InvalidArgument("cannot tell the mesh format of '" + path +
                           "'; name it .off, .obj, .ply or .stl");
  }
  if (!std::ifstream(path)) {
    return InvalidArgument("cannot open mesh file '" + path + "'");
  }
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, polygons);
  } catch (const std::exception& e) {
    return InvalidArgument("'" + path + "' is not a valid " + ext.substr(1) +
                           " file: " + e.what());
  }
  if (!ok) {
    return InvalidArgument("'" + path + "' is not a valid " + ext.substr(1) +
                           " mesh file (the reader stopped on it)");
  }
  if (points.size() > static_cast<size_t>(INT32_MAX)) {
    return InvalidArgument("'" + path + "' has more than 2^31 vertices");
  }
  out->vertices.reserve(points.size());
  for (const Point& p : points) out->vertices.push_back({p.x(), p.y(), p.z()});
  out->faces.reserve(polygons.size());
  for (size_t f = 0; f < polygons.size(); ++f) {
    std::vector<int32_t> face;
    for (std::size_t v : polygons[f]) {
      if (v >= points.size()) {
        return InvalidArgument("'" + path + "': face " + std::to_string(f) +
                               " has vertex index " + std::to_string(v) +
                               ", outside 0.." +
                               std::to_string(points.size() - 1));
      }
      face.push_back(static_cast<int32_t>(v));
    }
    out->faces.push_back(std::move(face));
  }
  for (size_t v = 0; v < out->vertices.size(); ++v) {
    if (!IsFinite(out->vertices[v])) {
      return InvalidArgument("'" + path + "': vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
    }
  }
  return OkStatus();
}

Status TriangulateSoup(const PolygonSoup& soup, MeshData* out) {
  out->vertices = soup.vertices;
  out->triangles.clear();
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    if (soup.faces[f].size() < 3) {
      return InvalidArgument("face " + std::to_string(f) + " has " +
                             std::to_string(soup.faces[f].size()) +
                             " corners; a face needs at least 3");
    }
    TriangulatePolygon(soup, soup.faces[f], &out->triangles);
  }
  return OkStatus();
}

Status ReadMeshFile(const std::string& path, MeshData* out) {
  PolygonSoup soup;
  Status s = ReadPolygonSoupFile(path, &soup);
  if (!s.ok()) return s;
  return TriangulateSoup(soup, out);
}

}  // namespace dot
