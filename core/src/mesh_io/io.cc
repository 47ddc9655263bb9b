// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "dot/control.h"
#include "mesh/normals.h"
#include "mesh_io/byte_order.h"
#include "mesh_io/mesh_formats.h"
#include "mesh_io/polygon_triangles.h"

namespace dot {
namespace {

std::string Extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool IsBlankOrComment(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

// OBJ index (1-based, negative from the end) to 0-based.
bool ObjIndex(long raw, size_t count, int32_t* out) {
  const long idx = raw > 0 ? raw - 1 : static_cast<long>(count) + raw;
  if (raw == 0 || idx < 0 || idx >= static_cast<long>(count)) return false;
  *out = static_cast<int32_t>(idx);
  return true;
}

}  // namespace

namespace {

// Drops the points at the end of a loop that repeat its first point (a loop
// closed by repeating its start, as many exporters write it), with a note.
void DropClosingRepeats(PolygonData* p, std::vector<std::string>* notes) {
  size_t dropped = 0;
  while (p->vertices.size() > 1 && p->vertices.back() == p->vertices.front()) {
    p->vertices.pop_back();
    if (!p->normals.empty()) p->normals.pop_back();
    ++dropped;
  }
  if (dropped > 0 && notes) {
    notes->push_back(
        dropped == 1
            ? "dropped the last vertex, a repeat of the first closing the loop"
            : "dropped the last " + std::to_string(dropped) +
                  " vertices, repeats of the first closing the loop");
  }
}

// Chains edges (pairs of vertex indices, in any direction and order) into
// closed loops, each starting with its first edge (in file order) in that
// edge's direction.
Status ChainEdges(const std::vector<std::pair<int32_t, int32_t>>& edges,
                  size_t vertex_count,
                  std::vector<std::vector<int32_t>>* loops) {
  const auto name = [](int32_t v) { return "vertex " + std::to_string(v + 1); };
  std::vector<std::vector<int32_t>> next(vertex_count);
  size_t used = 0;
  for (const auto& [a, b] : edges) {
    if (std::find(next[a].begin(), next[a].end(), b) != next[a].end()) {
      continue;  // the same edge again
    }
    used += next[a].empty() + next[b].empty();
    next[a].push_back(b);
    next[b].push_back(a);
  }
  for (size_t v = 0; v < vertex_count; ++v) {
    const size_t degree = next[v].size();
    if (degree == 1) {
      return InvalidArgument("the 'l' edges do not close into a loop: " +
                             name(static_cast<int32_t>(v)) +
                             " ends an open chain");
    }
    if (degree > 2) {
      return InvalidArgument(
          "the 'l' edges branch at " + name(static_cast<int32_t>(v)) + " (" +
          std::to_string(degree) +
          " edges); each loop of a polygon is a closed chain");
    }
  }
  std::vector<char> taken(vertex_count, 0);
  size_t chained = 0;
  loops->clear();
  for (const auto& [start, second] : edges) {
    if (taken[start]) continue;
    std::vector<int32_t> loop = {start};
    taken[start] = 1;
    int32_t prev = start, cur = second;
    while (cur != start) {
      loop.push_back(cur);
      taken[cur] = 1;
      const int32_t after = next[cur][0] == prev ? next[cur][1] : next[cur][0];
      prev = cur;
      cur = after;
    }
    chained += loop.size();
    loops->push_back(std::move(loop));
  }
  if (chained != used) {
    return InvalidArgument("the 'l' edges do not close into loops");
  }
  return OkStatus();
}

// Concatenates loops read one by one, dropping each one's closing repeats;
// with several, each must keep at least 3 vertices.
Status JoinLoops(std::vector<PolygonData> loops, PolygonData* out,
                 std::vector<std::string>* notes) {
  *out = {};
  for (size_t k = 0; k < loops.size(); ++k) {
    PolygonData& l = loops[k];
    DropClosingRepeats(&l, notes);
    if (loops.size() > 1 && l.vertices.size() < 3) {
      return InvalidArgument(
          "loop " + std::to_string(k + 1) + " has " +
          std::to_string(l.vertices.size()) +
          " distinct vertices once the repeats closing it are dropped; a "
          "loop needs at least 3");
    }
    out->vertices.insert(out->vertices.end(), l.vertices.begin(),
                         l.vertices.end());
    out->normals.insert(out->normals.end(), l.normals.begin(), l.normals.end());
    if (loops.size() > 1) {
      out->loop_sizes.push_back(static_cast<int32_t>(l.vertices.size()));
    }
  }
  if (loops.size() > 1 && notes) {
    // Said, since a stray blank line in a one-loop text file splits it.
    notes->push_back("read " + std::to_string(loops.size()) +
                     " loops (blank lines or separate 'l' loops separate "
                     "them): they bound one surface");
  }
  return OkStatus();
}

}  // namespace

Status ReadPolygonText(std::istream& in, PolygonData* out,
                       std::vector<std::string>* notes) {
  *out = {};
  std::vector<PolygonData> loops(1);
  int with_normals = -1;  // unknown until the first vertex line
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      // A blank line ends a loop.
      const size_t size = loops.back().vertices.size();
      if (size > 0 && size < 3) {
        return InvalidArgument(
            "line " + std::to_string(lineno) + ": a blank line ends loop " +
            std::to_string(loops.size()) + " after " + std::to_string(size) +
            (size == 1 ? " vertex" : " vertices") +
            "; a loop needs at least 3 (blank lines separate loops)");
      }
      if (size > 0) loops.emplace_back();
      continue;
    }
    if (IsBlankOrComment(line)) continue;
    std::istringstream s(line);
    std::vector<double> x;
    double d;
    while (s >> d) x.push_back(d);
    std::string rest;
    if (!s.eof() && (s.clear(), s >> rest)) {
      return InvalidArgument("line " + std::to_string(lineno) + ": '" + rest +
                             "' is not a number");
    }
    if (x.size() != 3 && x.size() != 6) {
      return InvalidArgument("line " + std::to_string(lineno) +
                             ": expected 3 (x y z)"
                             " or 6 (x y z nx ny nz) numbers, found " +
                             std::to_string(x.size()));
    }
    if (with_normals < 0) with_normals = x.size() == 6;
    if (with_normals != (x.size() == 6)) {
      return InvalidArgument("line " + std::to_string(lineno) +
                             ": some lines have normals and some do not");
    }
    loops.back().vertices.push_back({x[0], x[1], x[2]});
    if (x.size() == 6) loops.back().normals.push_back({x[3], x[4], x[5]});
  }
  if (loops.back().vertices.empty()) loops.pop_back();
  if (loops.size() > 1 && loops.back().vertices.size() < 3) {
    const size_t size = loops.back().vertices.size();
    return InvalidArgument(
        "the last loop (loop " + std::to_string(loops.size()) + ") has " +
        std::to_string(size) + (size == 1 ? " vertex" : " vertices") +
        "; a loop needs at least 3 (blank lines separate "
        "loops)");
  }
  if (loops.empty()) loops.emplace_back();
  return JoinLoops(std::move(loops), out, notes);
}

Status ReadPolygonObj(std::istream& in, PolygonData* out,
                      std::vector<std::string>* notes) {
  *out = {};
  std::vector<Vec3> v, vn;
  std::vector<std::vector<int32_t>> polylines;  // one per 'l' line
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v" || tag == "vn") {
      Vec3 p;
      if (!(s >> p.x >> p.y >> p.z)) {
        return InvalidArgument("line " + std::to_string(lineno) + ": bad '" +
                               tag + "' line");
      }
      (tag == "v" ? v : vn).push_back(p);
    } else if (tag == "l") {
      std::vector<int32_t> polyline;
      std::string tok;
      while (s >> tok) {
        int32_t idx;
        const long raw = std::strtol(tok.c_str(), nullptr, 10);
        if (!ObjIndex(raw, v.size(), &idx)) {
          return InvalidArgument("line " + std::to_string(lineno) +
                                 ": index '" + tok + "' is out of range");
        }
        polyline.push_back(idx);
      }
      if (polyline.empty()) continue;
      if (!polylines.empty() && polyline.size() < 2) {
        return InvalidArgument("line " + std::to_string(lineno) +
                               ": an 'l' line of one vertex is no edge");
      }
      polylines.push_back(std::move(polyline));
    }
  }
  std::vector<std::vector<int32_t>> ids(1);
  std::vector<int32_t>& loop = ids.front();
  if (polylines.size() == 1) {
    loop = std::move(polylines.front());
    if (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
  } else if (polylines.size() > 1) {
    if (polylines.front().size() < 2) {
      return InvalidArgument("the first 'l' line has one vertex: no edge");
    }
    std::vector<std::pair<int32_t, int32_t>> edges;
    for (const auto& polyline : polylines) {
      for (size_t i = 0; i + 1 < polyline.size(); ++i) {
        if (polyline[i] == polyline[i + 1]) {
          return InvalidArgument("an 'l' edge joins vertex " +
                                 std::to_string(polyline[i] + 1) +
                                 " to itself");
        }
        edges.emplace_back(polyline[i], polyline[i + 1]);
      }
    }
    const Status chained = ChainEdges(edges, v.size(), &ids);
    if (!chained.ok()) return chained;
  } else {
    for (size_t i = 0; i < v.size(); ++i)
      loop.push_back(static_cast<int32_t>(i));
  }
  if (!vn.empty() && vn.size() != v.size()) {
    return InvalidArgument(std::to_string(vn.size()) + " 'vn' normals for " +
                           std::to_string(v.size()) + " vertices");
  }
  std::vector<PolygonData> loops(ids.size());
  for (size_t l = 0; l < ids.size(); ++l) {
    for (int32_t i : ids[l]) {
      loops[l].vertices.push_back(v[i]);
      if (!vn.empty()) loops[l].normals.push_back(vn[i]);
    }
  }
  return JoinLoops(std::move(loops), out, notes);
}

Status ReadPolygonFile(const std::string& path, PolygonData* out,
                       std::vector<std::string>* notes) {
  errno = 0;
  std::ifstream in(path);
  if (!in) {
    return InvalidArgument(
        "cannot open polygon file '" + path + "'" +
        (errno ? std::string(": ") + std::strerror(errno) : std::string()));
  }
  Status s = Extension(path) == "obj" ? ReadPolygonObj(in, out, notes)
                                      : ReadPolygonText(in, out, notes);
  if (!s.ok()) s.message = path + ": " + s.message;
  return s;
}

Status WritePolygonText(std::ostream& out, const PolygonData& polygon) {
  out.precision(17);
  size_t loop = 0, loop_end = polygon.loop_sizes.empty()
                                  ? polygon.vertices.size()
                                  : polygon.loop_sizes[0];
  for (size_t i = 0; i < polygon.vertices.size(); ++i) {
    if (i == loop_end && ++loop < polygon.loop_sizes.size()) {
      out << '\n';  // a blank line between loops
      loop_end += polygon.loop_sizes[loop];
    }
    const Vec3& p = polygon.vertices[i];
    out << p.x << ' ' << p.y << ' ' << p.z;
    if (!polygon.normals.empty()) {
      const Vec3& n = polygon.normals[i];
      out << ' ' << n.x << ' ' << n.y << ' ' << n.z;
    }
    out << '\n';
  }
  return out ? OkStatus() : InvalidArgument("failed writing the polygon");
}

Status WritePolygonText(const std::string& path, const PolygonData& polygon) {
  std::ofstream out(path);
  if (!out) {
    return InvalidArgument("cannot write '" + path +
                           "': " + std::strerror(errno));
  }
  if (!WritePolygonText(out, polygon).ok() || !out.flush()) {
    return InvalidArgument("failed writing '" + path +
                           "': " + std::strerror(errno));
  }
  return OkStatus();
}

namespace {

// Binary little-endian PLY: doubles as they are, so nothing is rounded.
void WriteBinaryPly(std::ostream& out, const MeshData& mesh) {
  out << "ply\nformat binary_little_endian 1.0\nelement vertex "
      << mesh.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "element face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : mesh.vertices) {
    PutLittleEndian(out, p.x);
    PutLittleEndian(out, p.y);
    PutLittleEndian(out, p.z);
  }
  for (const Triangle& t : mesh.triangles) {
    PutLittleEndian<uint8_t>(out, 3);
    for (int32_t v : t) PutLittleEndian(out, v);
  }
}

// STL, what 3D printing takes: a soup of facets, each with its unit
// normal. Binary STL stores float32 (coordinates are rounded to single
// precision); ASCII STL is written with every digit.
Vec3 FacetNormal(const MeshData& mesh, const Triangle& t) {
  return Normalized(
      FaceCross(t, [&](int32_t v) -> const Vec3& { return mesh.vertices[v]; }));
}

void WriteBinaryStl(std::ostream& out, const MeshData& mesh) {
  std::string header = "binary STL written by dot";
  header.resize(80, ' ');
  out.write(header.data(), 80);
  PutLittleEndian(out, static_cast<uint32_t>(mesh.triangles.size()));
  auto put = [&out](const Vec3& p) {
    PutLittleEndian(out, static_cast<float>(p.x));
    PutLittleEndian(out, static_cast<float>(p.y));
    PutLittleEndian(out, static_cast<float>(p.z));
  };
  for (const Triangle& t : mesh.triangles) {
    put(FacetNormal(mesh, t));
    for (int32_t v : t) put(mesh.vertices[v]);
    PutLittleEndian<uint16_t>(out, 0);  // attribute byte count
  }
}

void WriteAsciiStl(std::ostream& out, const MeshData& mesh) {
  out << "solid dot\n";
  for (const Triangle& t : mesh.triangles) {
    const Vec3 n = FacetNormal(mesh, t);
    out << "facet normal " << n.x << ' ' << n.y << ' ' << n.z
        << "\n outer loop\n";
    for (int32_t v : t) {
      const Vec3& p = mesh.vertices[v];
      out << "  vertex " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    }
    out << " endloop\nendfacet\n";
  }
  out << "endsolid dot\n";
}

}  // namespace

Status WriteMesh(std::ostream& out, const std::string& format,
                 const MeshData& mesh, bool ascii) {
  out.precision(17);
  errno = 0;
  // The system's reason when a write failed (a full disk, a closed pipe).
  auto written = [&out] {
    out.flush();
    if (out) return OkStatus();
    return InvalidArgument(
        std::string("failed writing the mesh") +
        (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
  };
  if (format == "ply" && !ascii) {
    WriteBinaryPly(out, mesh);
    return written();
  }
  if (format == "stl") {
    if (!ascii && mesh.triangles.size() > UINT32_MAX) {
      return InvalidArgument("binary STL holds at most 2^32 - 1 triangles");
    }
    if (ascii) {
      WriteAsciiStl(out, mesh);
    } else {
      WriteBinaryStl(out, mesh);
    }
    return written();
  }
  if (format == "obj") {
    for (const Vec3& p : mesh.vertices)
      out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const Triangle& t : mesh.triangles)
      out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  } else if (format == "off") {
    out << "OFF\n"
        << mesh.vertices.size() << ' ' << mesh.triangles.size() << " 0\n";
    for (const Vec3& p : mesh.vertices)
      out << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const Triangle& t : mesh.triangles)
      out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  } else if (format == "ply") {
    out << "ply\nformat ascii 1.0\nelement vertex " << mesh.vertices.size()
        << "\nproperty double x\nproperty double y\nproperty double z\n"
        << "element face " << mesh.triangles.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const Vec3& p : mesh.vertices)
      out << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const Triangle& t : mesh.triangles)
      out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  } else {
    return InvalidArgument("unknown mesh format '" + format +
                           "'; use obj, ply, off or stl");
  }
  return written();
}

Status WriteSoup(std::ostream& out, const std::string& format,
                 const PolygonSoup& soup, bool ascii,
                 std::vector<std::string>* notes) {
  std::vector<std::string> ignored;
  if (notes == nullptr) notes = &ignored;
  bool triangles = true;
  for (FaceView f : soup.faces) triangles = triangles && f.size() == 3;
  if (format == "obj" || format == "ply" || (format == "off" && !triangles)) {
    out.precision(17);
    errno = 0;
    if (format == "obj") {
      WriteObjSoup(out, soup, notes);
    } else if (format == "ply") {
      WritePlySoup(out, soup, ascii, notes);
    } else {
      out << "OFF\n"
          << soup.vertices.size() << ' ' << soup.faces.size() << " 0\n";
      for (const Vec3& p : soup.vertices)
        out << p.x << ' ' << p.y << ' ' << p.z << '\n';
      for (FaceView f : soup.faces) {
        out << f.size();
        for (int32_t v : f) out << ' ' << v;
        out << '\n';
      }
    }
    out.flush();
    if (!out) {
      return InvalidArgument(
          std::string("failed writing the mesh") +
          (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
    }
  } else {
    // OFF of triangles and STL: the triangle writer (STL has no polygons:
    // they are triangulated as the readers do).
    MeshData mesh{soup.vertices, {}};
    for (FaceView f : soup.faces) {
      const Status s =
          TriangulatePolygon(soup.vertices, f, Control{}, &mesh.triangles);
      if (!s.ok()) return s;
    }
    const Status s = WriteMesh(out, format, mesh, ascii);
    if (!s.ok()) return s;
  }
  if (format == "off" || format == "stl") {
    for (const AttributeChannel& ch : soup.attributes) {
      notes->push_back("attribute '" + ch.name + "' not written: " + format +
                       " has no place for it (PLY and OBJ keep it)");
    }
  }
  return OkStatus();
}

namespace {

// A mesh file opened for writing, its format from the extension.
Status OpenMeshFile(const std::string& path, std::string* ext,
                    std::ofstream* out) {
  *ext = Extension(path);
  if (*ext != "obj" && *ext != "ply" && *ext != "off" && *ext != "stl") {
    return InvalidArgument("cannot tell the mesh format of '" + path +
                           "'; name it .obj, .ply, .off or .stl");
  }
  out->open(path, std::ios::binary);
  if (!*out) {
    return InvalidArgument("cannot write '" + path +
                           "': " + std::strerror(errno));
  }
  return OkStatus();
}

}  // namespace

Status WriteSoupFile(const std::string& path, const PolygonSoup& soup,
                     bool ascii, std::vector<std::string>* notes) {
  std::string ext;
  std::ofstream out;
  const Status s = OpenMeshFile(path, &ext, &out);
  return s.ok() ? WriteSoup(out, ext, soup, ascii, notes) : s;
}

Status WriteMeshFile(const std::string& path, const MeshData& mesh,
                     bool ascii) {
  std::string ext;
  std::ofstream out;
  const Status s = OpenMeshFile(path, &ext, &out);
  return s.ok() ? WriteMesh(out, ext, mesh, ascii) : s;
}

}  // namespace dot
