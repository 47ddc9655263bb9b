// SPDX-License-Identifier: AGPL-3.0-or-later
// Mesh readers: CGAL's polygon-soup I/O (OFF, OBJ, PLY, STL; ASCII and
// binary), a well-kept library rather than four parsers of our own.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OFF/File_scanner_OFF.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "dot/io.h"
#include "dot/triangulate.h"
#include "mesh_io/mesh_formats.h"
#include "mesh_io/off_fast.h"
#include "mesh_io/polygon_triangles.h"
#include "util/run_control.h"

namespace dot {
namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

std::string LowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// CGAL 5.5's PLY reader trusts the header where only its debug assertions
// check it (found by mesh_file_fuzz): a "property" line before any
// "element" indexes an empty vector, and a vertex coordinate (x, y, z) that
// is not a float or double scalar is read through a null pointer. Such
// headers, a property named twice in one element (the reader would check
// one and read the other), types it does not know (it reads nothing for
// them) and item counts the file cannot hold (it pushes back that many
// points, "-4" being 2^64 - 4) are refused here first, as are list counts
// wider than 16 bits (below).
Status CheckPlyHeader(const std::string& path) {
  static const std::set<std::string> kPlyTypes = {
      "char",  "uchar",  "short",   "ushort", "int",   "uint",
      "float", "double", "int8",    "uint8",  "int16", "uint16",
      "int32", "uint32", "float32", "float64"};
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) return InvalidArgument("cannot read '" + path + "'");
  std::ifstream in(path, std::ios::binary);
  const auto refuse = [&](const std::string& why) {
    return InvalidArgument("'" + path + "' is not a valid ply file: " + why);
  };
  std::string line, element;
  bool has_element = false;
  std::set<std::string> names;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string word, type, name;
    words >> word;
    if (word == "end_header") break;
    if (word == "element") {
      std::string count;
      words >> element >> count;
      // Each item takes at least a byte (CGAL reads a count of items, each
      // pushed back, even when it has no property it knows).
      if (count.empty() || count.size() > 19 ||
          count.find_first_not_of("0123456789") != std::string::npos ||
          std::stoull(count) > bytes) {
        return refuse("element '" + element + "' has a count of '" + count +
                      "' items, which a file of " + std::to_string(bytes) +
                      " bytes cannot hold");
      }
      has_element = true;
      names.clear();
    } else if (word == "property") {
      if (!has_element) return refuse("a property before any element");
      words >> type;
      std::string count_type, item = type;
      if (type == "list") words >> count_type >> item;
      words >> name;
      if (!kPlyTypes.count(item) ||
          (type == "list" && !kPlyTypes.count(count_type))) {
        return refuse("property '" + name + "' has an unknown type");
      }
      // CGAL resizes a list to the count it reads before reading its items:
      // a 32-bit count could claim 16 GB. Faces are written with 8-bit
      // counts ("list uchar int") by CGAL, Blender, MeshLab and dot.
      if (type == "list" && count_type != "uchar" && count_type != "uint8" &&
          count_type != "char" && count_type != "int8" &&
          count_type != "ushort" && count_type != "uint16" &&
          count_type != "short" && count_type != "int16") {
        return refuse("list property '" + name + "' has " + count_type +
                      " counts; dot reads lists with 8- or 16-bit counts "
                      "(re-save it as 'list uchar int')");
      }
      if (!names.insert(name).second) {
        return refuse("property '" + name + "' twice in element '" + element +
                      "'");
      }
      const bool vertex = element == "vertex" || element == "vertices";
      const bool coordinate = name == "x" || name == "y" || name == "z";
      if (vertex && coordinate && type != "float" && type != "float32" &&
          type != "double" && type != "float64") {
        return refuse("vertex coordinate '" + name + "' is of type '" + type +
                      "'; it must be float or double");
      }
    }
  }
  return OkStatus();
}

// OFF through CGAL's own scanner, as CGAL::IO::read_OFF reads it, but with
// every count bounded by the file's size before anything is allocated:
// CGAL 5.5 resizes to the counts the file states, so a 70-byte file
// claiming a face of 2*10^9 corners made it allocate 16 GB (found by
// mesh_file_fuzz). Each vertex, face and corner takes at least one byte.
// The text item that starts at or after byte `offset` of the file at
// `path`: its 1-based line, and that line's words (none at the end).
struct OffItem {
  size_t line = 1;
  std::vector<std::string> words;
};
// A file read through a 1 MiB buffer that knows its position: tellg is
// then arithmetic, where std::filebuf makes a system call (lseek) each time,
// and ReadOff asks before every vertex and face (a tenth of a large fill's
// time went there). One character stays available for putback across
// refills, as the OFF scanner needs.
class PositionedFileBuf : public std::streambuf {
 public:
  explicit PositionedFileBuf(const std::string& path)
      : file_(std::fopen(path.c_str(), "rb")), buffer_(1 << 20) {}
  ~PositionedFileBuf() override {
    if (file_ != nullptr) std::fclose(file_);
  }
  bool is_open() const { return file_ != nullptr; }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (file_ == nullptr) return traits_type::eof();
    const size_t keep = egptr() > eback() ? 1 : 0;
    const auto used = static_cast<std::streamoff>(egptr() - eback());
    if (keep == 1) buffer_[0] = egptr()[-1];
    start_ += used - static_cast<std::streamoff>(keep);
    const size_t n =
        std::fread(buffer_.data() + keep, 1, buffer_.size() - keep, file_);
    setg(buffer_.data(), buffer_.data() + keep, buffer_.data() + keep + n);
    return n == 0 ? traits_type::eof() : traits_type::to_int_type(*gptr());
  }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir,
                   std::ios_base::openmode) override {
    if (off != 0 || dir != std::ios_base::cur) return pos_type(off_type(-1));
    return pos_type(start_ + (gptr() - eback()));
  }

 private:
  std::FILE* file_;
  std::vector<char> buffer_;
  std::streamoff start_ = 0;  // the file offset of eback()
};

OffItem ItemAt(const std::string& path, std::streamoff offset) {
  std::ifstream in(path, std::ios::binary);
  OffItem item;
  char c;
  for (std::streamoff i = 0; i < offset && in.get(c); ++i)
    item.line += c == '\n';
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
    item.line += c == '\n';
  }
  if (!in) return item;
  std::string text(1, c), rest;
  std::getline(in, rest);
  std::istringstream words(text + rest);
  for (std::string w; words >> w && w[0] != '#';) item.words.push_back(w);
  return item;
}

// Straight into the flat soup: the reader holds no second copy.
Status ReadOff(const std::string& path, PolygonSoup* out,
               std::vector<std::string>* notes) {
  std::error_code ec;
  const auto bytes =
      static_cast<std::size_t>(std::filesystem::file_size(path, ec));
  if (ec) return InvalidArgument("cannot read mesh file '" + path + "'");
  PositionedFileBuf file(path);
  if (!file.is_open()) {
    return InvalidArgument("cannot read mesh file '" + path + "'");
  }
  std::istream in(&file);
  bool binary = false;            // "OFF BINARY": no lines to name
  std::streamoff item_start = 0;  // where the vertex or face being read began
  OffItem item;
  // Why the item that begins at item_start could not be read, by line.
  auto at = [&](const std::string& what) {
    if (binary) return InvalidArgument("'" + path + "': " + what);
    return InvalidArgument("'" + path + "' line " + std::to_string(item.line) +
                           ": " + what);
  };
  auto begin_item = [&] {
    in.clear(in.rdstate() & ~std::ios::failbit);
    item_start = in.tellg();
  };
  auto read_item = [&] {
    in.clear();
    item = ItemAt(path, item_start);
    return item.words;
  };
  if (bytes == 0) return InvalidArgument("'" + path + "' is empty");
  CGAL::File_scanner_OFF scanner(in);
  binary = scanner.binary();
  if (in.fail()) {
    return InvalidArgument("'" + path +
                           "' has no OFF header ('OFF', then the counts of "
                           "vertices, faces and edges)");
  }
  if (scanner.size_of_vertices() > bytes || scanner.size_of_facets() > bytes) {
    return InvalidArgument(
        "'" + path + "' declares " +
        std::to_string(scanner.size_of_vertices()) + " vertices and " +
        std::to_string(scanner.size_of_facets()) + " faces, more than its " +
        std::to_string(bytes) + " bytes can hold");
  }
  std::vector<Vec3>& points = out->vertices;
  points.resize(scanner.size_of_vertices());
  // NOFF normals, COFF colours and STOFF texture coordinates, per vertex.
  AttributeChannel normal{"normal", 3, {}, {}}, color{"color", 3, {}, {}},
      uv{"uv", 2, {}, {}};
  for (std::size_t v = 0; v < points.size(); ++v) {
    double x = 0, y = 0, z = 0, w = 1, nx = 0, ny = 0, nz = 0, s = 0, t = 0;
    unsigned char r = 0, g = 0, b = 0;
    begin_item();
    scanner.scan_vertex(x, y, z, w);
    if (scanner.has_normals()) {
      scanner.scan_normal(nx, ny, nz);
      normal.values.insert(normal.values.end(),
                           {float(nx), float(ny), float(nz)});
    }
    if (scanner.has_vcolors()) {
      scanner.scan_color(r, g, b);
      color.values.insert(color.values.end(),
                          {r / 255.0f, g / 255.0f, b / 255.0f});
    }
    if (scanner.has_textures()) {
      scanner.scan_texture(s, t);
      uv.values.insert(uv.values.end(), {float(s), float(t)});
    }
    if (!in.good()) {
      const std::vector<std::string> words = read_item();
      std::string bad;
      for (const std::string& word : words) {
        char* end = nullptr;
        const double value = std::strtod(word.c_str(), &end);
        if (*end != '\0' || !std::isfinite(value)) {
          bad = word;
          break;
        }
      }
      return at("vertex " + std::to_string(v) + " of " +
                std::to_string(points.size()) +
                (words.empty() ? ": the file ends before it"
                 : bad.empty() ? ": too few coordinates"
                               : ": '" + bad + "' is not a finite number"));
    }
    if (w == 0) return at("vertex " + std::to_string(v) + " has w = 0");
    points[v] = {x / w, y / w, z / w};
  }
  const std::size_t faces = scanner.size_of_facets();
  out->faces.reserve(faces);
  std::vector<int32_t> face;
  std::size_t corners = 0;
  for (std::size_t f = 0; f < faces; ++f) {
    std::size_t no = std::size_t(-1);
    begin_item();
    scanner.scan_facet(no, f);
    if ((!in.eof() && !in.good()) || no == std::size_t(-1)) {
      return at("face " + std::to_string(f) + " of " + std::to_string(faces) +
                (read_item().empty() ? ": the file ends before it"
                                     : ": its corner count is not a number"));
    }
    corners += no;
    if (no > bytes || corners > bytes) {
      read_item();
      return at("face " + std::to_string(f) + " declares " +
                std::to_string(no) + " corners, more than the file holds");
    }
    face.resize(no);
    for (std::size_t j = 0; j < no; ++j) {
      std::size_t v = 0;
      scanner.scan_facet_vertex_index(v, j + 1, f);
      if (!in) {
        const std::vector<std::string> words = read_item();
        const std::string word = j + 1 < words.size() ? words[j + 1] : "";
        char* end = nullptr;
        const long long index = std::strtoll(word.c_str(), &end, 10);
        if (word.empty()) {
          return at("face " + std::to_string(f) + " has fewer than its " +
                    std::to_string(no) + " corners");
        }
        if (*end != '\0') {
          return at("face " + std::to_string(f) + ", corner " +
                    std::to_string(j) + ": '" + word +
                    "' is not a vertex index");
        }
        return at("face " + std::to_string(f) + " has vertex index " +
                  std::to_string(index) + ", outside 0.." +
                  std::to_string(points.size() - 1));
      }
      if (v >= points.size()) {
        read_item();
        return at("face " + std::to_string(f) + " has vertex index " +
                  std::to_string(v) + ", outside 0.." +
                  std::to_string(points.size() - 1));
      }
      face[j] = static_cast<int32_t>(v);
    }
    out->faces.Add(face.begin(), face.end());
    if (scanner.has_fcolors()) {
      unsigned char r = 0, g = 0, b = 0;
      scanner.scan_color(r, g, b);
    }
  }
  for (AttributeChannel* ch : {&normal, &color, &uv}) {
    if (!ch->values.empty()) out->attributes.push_back(std::move(*ch));
  }
  if (scanner.has_fcolors() && notes != nullptr) {
    notes->push_back("'" + path +
                     "': per-face colours are skipped (dot "
                     "keeps per-vertex and per-corner attributes)");
  }
  if (in.fail() && !in.eof()) {
    read_item();
    return at("the file does not parse here");
  }
  return OkStatus();
}

// OBJ, PLY and STL through CGAL's polygon-soup reader, then into the flat
// soup, each reader copy released as it is converted.
Status ReadWithCgal(const std::string& path, const std::string& ext,
                    PolygonSoup* out) {
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
  const size_t n = points.size();
  out->vertices.reserve(n);
  for (const Point& p : points) out->vertices.push_back({p.x(), p.y(), p.z()});
  std::vector<Point>().swap(points);
  out->faces.reserve(polygons.size());
  for (size_t f = 0; f < polygons.size(); ++f) {
    for (std::size_t v : polygons[f]) {
      if (v >= n) {
        return InvalidArgument("'" + path + "': face " + std::to_string(f) +
                               " has vertex index " + std::to_string(v) +
                               ", outside 0.." + std::to_string(n - 1));
      }
    }
    out->faces.Add(polygons[f].begin(), polygons[f].end());
    std::vector<std::size_t>().swap(polygons[f]);
  }
  return OkStatus();
}

}  // namespace

Status TriangulatePolygon(const std::vector<Vec3>& vertices, FaceView f,
                          const Control& control, std::vector<Triangle>* out) {
  if (f.size() > 3) {
    Problem p;
    for (int32_t v : f) p.vertices.push_back(vertices[v]);
    const Result r = Triangulate(p, Options{}, control);
    if (r.status.code == StatusCode::kCancelled ||
        r.status.code == StatusCode::kDeadlineExceeded) {
      return r.status;
    }
    if (r.status.ok() && r.inserted.empty()) {
      for (const Triangle& t : r.triangles) {
        out->push_back({f[t[0]], f[t[1]], f[t[2]]});
      }
      return OkStatus();
    }
  }
  for (size_t k = 1; k + 1 < f.size(); ++k) {
    out->push_back({f[0], f[k], f[k + 1]});
  }
  return OkStatus();
}

Status ReadPolygonSoupFile(const std::string& path, PolygonSoup* out,
                           std::vector<std::string>* notes) {
  *out = {};
  const std::string ext = LowerExtension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") {
    return InvalidArgument("cannot tell the mesh format of '" + path +
                           "'; name it .off, .obj, .ply or .stl");
  }
  if (!std::ifstream(path)) {
    return InvalidArgument("cannot open mesh file '" + path + "'");
  }
  if (ext == ".ply") {
    const Status header = CheckPlyHeader(path);
    if (!header.ok()) return header;
  }
  if (ext == ".off" || ext == ".ply" || ext == ".obj") {
    if (ext == ".off" && ReadPlainOffFast(path, out)) return OkStatus();
    const Status s = ext == ".off"   ? ReadOff(path, out, notes)
                     : ext == ".ply" ? ReadPlyMesh(path, out, notes)
                                     : ReadObjMesh(path, out, notes);
    if (!s.ok()) return s;
  } else {
    const Status s = ReadWithCgal(path, ext, out);
    if (!s.ok()) return s;
  }
  for (size_t v = 0; v < out->vertices.size(); ++v) {
    if (!IsFinite(out->vertices[v])) {
      return InvalidArgument("'" + path + "': vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
    }
  }
  const Status attributes = CheckAttributes(*out);
  if (!attributes.ok()) {
    return InvalidArgument("'" + path + "': " + attributes.message);
  }
  return OkStatus();
}

Status CheckAttributes(const PolygonSoup& soup) {
  for (const AttributeChannel& ch : soup.attributes) {
    const std::string name = "attribute '" + ch.name + "'";
    if (ch.dims < 1 || ch.dims > 16) {
      return InvalidArgument(name + " has " + std::to_string(ch.dims) +
                             " values an entry; 1 to 16 are allowed");
    }
    if (ch.values.size() % ch.dims != 0) {
      return InvalidArgument(name + " has " + std::to_string(ch.values.size()) +
                             " values, not a multiple of its " +
                             std::to_string(ch.dims) + " an entry");
    }
    for (size_t i = 0; i < ch.values.size(); ++i) {
      if (!std::isfinite(ch.values[i])) {
        return InvalidArgument(name + ": entry " + std::to_string(i / ch.dims) +
                               " is not finite");
      }
    }
    if (!ch.per_corner()) {
      if (ch.entries() != soup.vertices.size()) {
        return InvalidArgument(
            name + " has " + std::to_string(ch.entries()) + " entries for " +
            std::to_string(soup.vertices.size()) + " vertices");
      }
      continue;
    }
    if (ch.indices.size() != soup.faces.corners()) {
      return InvalidArgument(
          name + " has " + std::to_string(ch.indices.size()) +
          " corner indices for " + std::to_string(soup.faces.corners()) +
          " face corners");
    }
    for (size_t c = 0; c < ch.indices.size(); ++c) {
      if (ch.indices[c] < 0 ||
          static_cast<size_t>(ch.indices[c]) >= ch.entries()) {
        return InvalidArgument(name + ": corner " + std::to_string(c) +
                               " names entry " + std::to_string(ch.indices[c]) +
                               ", outside 0.." +
                               std::to_string(int64_t(ch.entries()) - 1));
      }
    }
  }
  return OkStatus();
}

Status TriangulateSoup(const PolygonSoup& soup, MeshData* out) {
  return TriangulateSoup(soup, Control{}, out);
}

Status TriangulateSoup(const PolygonSoup& soup, const Control& control,
                       MeshData* out, std::vector<int32_t>* face_of) {
  out->vertices = soup.vertices;
  out->triangles.clear();
  if (face_of != nullptr) face_of->clear();
  RunTicker ticker(control, "the triangulation of the mesh's polygons");
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    if (soup.faces[f].size() < 3) {
      return InvalidArgument("face " + std::to_string(f) + " has " +
                             std::to_string(soup.faces[f].size()) +
                             " corners; a face needs at least 3");
    }
    if (!ticker.Tick()) return ticker.status();
    const Status s = TriangulatePolygon(soup.vertices, soup.faces[f], control,
                                        &out->triangles);
    if (!s.ok()) return s;
    if (face_of != nullptr) {
      face_of->resize(out->triangles.size(), static_cast<int32_t>(f));
    }
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
