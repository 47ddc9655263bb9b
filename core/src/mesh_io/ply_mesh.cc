// SPDX-License-Identifier: AGPL-3.0-or-later
// PLY meshes with their attributes (mesh_formats.h). The header has been
// checked by CheckPlyHeader (mesh_files.cc) before this reader runs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>

#include "mesh_io/byte_order.h"
#include "mesh_io/mesh_formats.h"

namespace dot {
namespace {

enum class Type {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat,
  kDouble
};

bool ParseType(const std::string& s, Type* t) {
  static const std::map<std::string, Type> kTypes = {
      {"char", Type::kInt8},     {"int8", Type::kInt8},
      {"uchar", Type::kUint8},   {"uint8", Type::kUint8},
      {"short", Type::kInt16},   {"int16", Type::kInt16},
      {"ushort", Type::kUint16}, {"uint16", Type::kUint16},
      {"int", Type::kInt32},     {"int32", Type::kInt32},
      {"uint", Type::kUint32},   {"uint32", Type::kUint32},
      {"float", Type::kFloat},   {"float32", Type::kFloat},
      {"double", Type::kDouble}, {"float64", Type::kDouble}};
  auto it = kTypes.find(s);
  if (it == kTypes.end()) return false;
  *t = it->second;
  return true;
}

size_t Size(Type t) {
  switch (t) {
    case Type::kInt8:
    case Type::kUint8:
      return 1;
    case Type::kInt16:
    case Type::kUint16:
      return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat:
      return 4;
    case Type::kDouble:
      return 8;
  }
  return 8;
}

// Colours stored as integers are scaled to [0, 1] by their type's maximum.
double IntegerMax(Type t) {
  switch (t) {
    case Type::kUint8:
      return 255;
    case Type::kUint16:
      return 65535;
    case Type::kInt8:
      return 127;
    case Type::kInt16:
      return 32767;
    default:
      return 1;
  }
}

struct Property {
  std::string name;
  Type type = Type::kFloat;
  bool list = false;
  Type count_type = Type::kUint8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

// Values in the file's encoding.
class Values {
 public:
  Values(std::istream& in, int format) : in_(in), format_(format) {}
  bool Read(Type t, double* out) {
    if (format_ == 0) return static_cast<bool>(in_ >> *out);
    char b[8];
    const size_t n = Size(t);
    if (!in_.read(b, static_cast<std::streamsize>(n))) return false;
    const bool swap = (format_ == 1) != kLittleEndianHost;
    if (swap) std::reverse(b, b + n);
    switch (t) {
      case Type::kInt8:
        *out = static_cast<int8_t>(b[0]);
        break;
      case Type::kUint8:
        *out = static_cast<uint8_t>(b[0]);
        break;
      case Type::kInt16:
        *out = Get<int16_t>(b);
        break;
      case Type::kUint16:
        *out = Get<uint16_t>(b);
        break;
      case Type::kInt32:
        *out = Get<int32_t>(b);
        break;
      case Type::kUint32:
        *out = Get<uint32_t>(b);
        break;
      case Type::kFloat:
        *out = Get<float>(b);
        break;
      case Type::kDouble:
        *out = Get<double>(b);
        break;
    }
    return true;
  }

 private:
  template <typename T>
  static T Get(const char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  std::istream& in_;
  int format_;  // 0 ascii, 1 little endian, 2 big endian
};

// Where a vertex property goes.
struct Target {
  int channel = -1;   // index into the soup's channels, -1: a coordinate
  int component = 0;  // x, y, z or the channel's component
  double scale = 1;
  bool skip = false;
};

}  // namespace

Status ReadPlyMesh(const std::string& path, PolygonSoup* out,
                   std::vector<std::string>* notes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return InvalidArgument("cannot open mesh file '" + path + "'");
  const auto refuse = [&](const std::string& why) {
    return InvalidArgument("'" + path + "' is not a valid ply file: " + why);
  };
  std::string line;
  int format = -1;
  std::vector<Element> elements;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") break;
    if (word == "format") {
      std::string f;
      words >> f;
      format = f == "ascii"                  ? 0
               : f == "binary_little_endian" ? 1
               : f == "binary_big_endian"    ? 2
                                             : -1;
      if (format < 0) return refuse("unknown format '" + f + "'");
    } else if (word == "element") {
      Element& e = elements.emplace_back();
      words >> e.name >> e.count;
    } else if (word == "property" && !elements.empty()) {
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type;
        words >> count_type >> type;
        p.list = true;
        ParseType(count_type, &p.count_type);
      }
      ParseType(type, &p.type);
      words >> p.name;
      elements.back().properties.push_back(p);
    }
  }
  if (format < 0) return refuse("no format line before end_header");
  // Each item of an element takes at least a byte per property (a list, at
  // least its count): a header cannot make the reader allocate more than
  // the file holds.
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  for (const Element& e : elements) {
    const uint64_t per_item = std::max<size_t>(1, e.properties.size());
    if (ec || e.count > bytes / per_item) {
      return refuse("element '" + e.name + "' claims " +
                    std::to_string(e.count) + " items of " +
                    std::to_string(per_item) +
                    " properties, more than the file's " +
                    std::to_string(bytes) + " bytes hold");
    }
  }
  Values values(in, format);
  std::vector<float> uv_corners;  // face texcoord lists
  bool corner_uvs = true;
  for (const Element& e : elements) {
    const bool is_vertex = e.name == "vertex" || e.name == "vertices";
    const bool is_face = e.name == "face" || e.name == "faces";
    if (!is_vertex && !is_face && notes != nullptr) {
      notes->push_back("'" + path + "': element '" + e.name +
                       "' is skipped (dot keeps vertices and faces)");
    }
    std::vector<Target> targets(e.properties.size());
    std::vector<bool> xyz(3, false);
    if (is_vertex) {
      if (!out->vertices.empty()) return refuse("a second vertex element");
      auto channel = [&](const std::string& name, int dims) {
        for (size_t c = 0; c < out->attributes.size(); ++c) {
          if (out->attributes[c].name == name) return static_cast<int>(c);
        }
        out->attributes.push_back({name, dims, {}, {}});
        return static_cast<int>(out->attributes.size() - 1);
      };
      // A property of a channel's own name ("color") stays apart from the
      // channel made of red, green, blue.
      auto own_name = [](const std::string& name) {
        return name == "color" || name == "normal" || name == "uv"
                   ? "ply_" + name
                   : name;
      };
      static const std::map<std::string, std::pair<std::string, int>> kKnown = {
          {"nx", {"normal", 0}},    {"ny", {"normal", 1}},
          {"nz", {"normal", 2}},    {"red", {"color", 0}},
          {"green", {"color", 1}},  {"blue", {"color", 2}},
          {"alpha", {"color", 3}},  {"s", {"uv", 0}},
          {"t", {"uv", 1}},         {"u", {"uv", 0}},
          {"v", {"uv", 1}},         {"texture_u", {"uv", 0}},
          {"texture_v", {"uv", 1}}, {"texture_s", {"uv", 0}},
          {"texture_t", {"uv", 1}}};
      // Channels of known names are made only when complete.
      auto has = [&](const char* n) {
        return std::any_of(e.properties.begin(), e.properties.end(),
                           [&](const Property& p) { return p.name == n; });
      };
      const bool normal = has("nx") && has("ny") && has("nz");
      const bool color = has("red") && has("green") && has("blue");
      const char* uv_names[][2] = {{"s", "t"},
                                   {"u", "v"},
                                   {"texture_u", "texture_v"},
                                   {"texture_s", "texture_t"}};
      std::string uv_u, uv_v;
      for (const auto& pair : uv_names) {
        if (uv_u.empty() && has(pair[0]) && has(pair[1])) {
          uv_u = pair[0];
          uv_v = pair[1];
        }
      }
      for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        Target& t = targets[i];
        if (p.name == "x" || p.name == "y" || p.name == "z") {
          t.component = p.name[0] - 'x';
          xyz[t.component] = true;
          continue;
        }
        auto known = kKnown.find(p.name);
        const bool used = known != kKnown.end() &&
                          ((known->second.first == "normal" && normal) ||
                           (known->second.first == "color" && color) ||
                           (known->second.first == "uv" &&
                            (p.name == uv_u || p.name == uv_v)));
        if (p.list) {
          t.skip = true;
          if (notes != nullptr) {
            notes->push_back("'" + path + "': vertex list property '" + p.name +
                             "' is skipped");
          }
        } else if (used) {
          const std::string& name = known->second.first;
          t.channel = channel(name, name == "normal" ? 3
                                    : name == "uv"   ? 2
                                    : has("alpha")   ? 4
                                                     : 3);
          t.component = known->second.second;
          if (name == "color") t.scale = 1 / IntegerMax(p.type);
        } else {
          t.channel = channel(own_name(p.name), 1);
        }
      }
      if (!xyz[0] || !xyz[1] || !xyz[2]) {
        return refuse("element '" + e.name + "' lacks x, y or z");
      }
      out->vertices.resize(e.count);
      for (AttributeChannel& ch : out->attributes) {
        ch.values.assign(e.count * ch.dims, 0.0f);
      }
    }
    int vertex_list = -1, texcoord_list = -1;
    if (is_face) {
      for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (p.list && vertex_list < 0 &&
            (p.name == "vertex_indices" || p.name == "vertex_index")) {
          vertex_list = static_cast<int>(i);
        } else if (p.list && p.name == "texcoord") {
          texcoord_list = static_cast<int>(i);
        } else if (notes != nullptr) {
          notes->push_back("'" + path + "': face property '" + p.name +
                           "' is skipped (dot keeps per-vertex and per-corner "
                           "attributes)");
        }
      }
      if (vertex_list < 0) {
        return refuse("element '" + e.name + "' has no vertex_indices list");
      }
    }
    std::vector<int32_t> face;
    for (uint64_t item = 0; item < e.count; ++item) {
      const auto bad = [&](const std::string& what) {
        return refuse(e.name + " " + std::to_string(item) + " of " +
                      std::to_string(e.count) + ": " + what);
      };
      face.clear();
      for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        double x = 0;
        if (!p.list) {
          if (!values.Read(p.type, &x)) {
            return bad("property '" + p.name + "' cannot be read");
          }
          if (!is_vertex) continue;
          const Target& t = targets[i];
          if (t.skip) continue;
          if (t.channel < 0) {
            Vec3& v = out->vertices[item];
            (t.component == 0 ? v.x : t.component == 1 ? v.y : v.z) = x;
          } else {
            AttributeChannel& ch = out->attributes[t.channel];
            ch.values[item * ch.dims + t.component] =
                static_cast<float>(x * t.scale);
          }
          continue;
        }
        double count = 0;
        if (!values.Read(p.count_type, &count) || count < 0 || count > 65535) {
          return bad("the count of list '" + p.name + "' cannot be read");
        }
        for (int k = 0; k < static_cast<int>(count); ++k) {
          if (!values.Read(p.type, &x)) {
            return bad("list '" + p.name + "' ends before its " +
                       std::to_string(static_cast<int>(count)) + " items");
          }
          if (static_cast<int>(i) == vertex_list) {
            if (!(x >= 0 && x <= 2147483647.0)) {  // NaN too
              return bad("vertex index " + std::to_string(x) + " is invalid");
            }
            face.push_back(static_cast<int32_t>(x));
          } else if (static_cast<int>(i) == texcoord_list) {
            uv_corners.push_back(static_cast<float>(x));
          }
        }
        if (static_cast<int>(i) == texcoord_list &&
            static_cast<size_t>(count) != 2 * face.size()) {
          corner_uvs = false;
        }
      }
      if (is_face) {
        if (face.size() < 3) {
          return bad("a face needs at least 3 corners; it has " +
                     std::to_string(face.size()));
        }
        out->faces.Add(face.begin(), face.end());
      }
    }
  }
  const size_t n = out->vertices.size();
  for (size_t f = 0; f < out->faces.size(); ++f) {
    for (int32_t v : out->faces[f]) {
      if (static_cast<size_t>(v) >= n) {
        return InvalidArgument("'" + path + "': face " + std::to_string(f) +
                               " has vertex index " + std::to_string(v) +
                               ", outside 0.." +
                               std::to_string(int64_t(n) - 1));
      }
    }
  }
  if (!uv_corners.empty()) {
    const bool vertex_uv =
        std::any_of(out->attributes.begin(), out->attributes.end(),
                    [](const AttributeChannel& c) { return c.name == "uv"; });
    if (corner_uvs && !vertex_uv &&
        uv_corners.size() == 2 * out->faces.corners()) {
      std::vector<int32_t> indices(out->faces.corners());
      for (size_t c = 0; c < indices.size(); ++c)
        indices[c] = static_cast<int32_t>(c);
      out->attributes.push_back(
          {"uv", 2, std::move(uv_corners), std::move(indices)});
    } else if (notes != nullptr) {
      notes->push_back(
          "'" + path + "': face texcoord lists are skipped (" +
          std::string(vertex_uv ? "the vertices have uv" : "not 2 per corner") +
          ")");
    }
  }
  return OkStatus();
}

void WritePlySoup(std::ostream& out, const PolygonSoup& soup, bool ascii,
                  std::vector<std::string>* notes) {
  // Vertices as written: one per distinct (vertex, per-corner entries).
  std::vector<int32_t> source;         // written vertex -> soup vertex
  std::vector<int32_t> corner_vertex;  // per corner, the written vertex
  std::vector<int32_t> keys;  // its per-corner entries (seamed.size() each)
  std::vector<const AttributeChannel*> seamed;
  for (const AttributeChannel& ch : soup.attributes) {
    if (ch.per_corner()) seamed.push_back(&ch);
  }
  if (seamed.empty()) {
    source.resize(soup.vertices.size());
    for (size_t v = 0; v < source.size(); ++v)
      source[v] = static_cast<int32_t>(v);
    corner_vertex = soup.faces.indices();
  } else {
    // Entries of equal value are one (an OBJ names a vt per corner): the
    // entries sorted by their bytes, each run named by its first.
    const size_t n_seamed = seamed.size();
    std::vector<std::vector<int32_t>> canonical(n_seamed);
    for (size_t s = 0; s < n_seamed; ++s) {
      const AttributeChannel& ch = *seamed[s];
      const size_t width = sizeof(float) * ch.dims;
      std::vector<int32_t> order(ch.entries());
      for (size_t e = 0; e < order.size(); ++e) order[e] = int32_t(e);
      auto cmp = [&](int32_t x, int32_t y) {
        return std::memcmp(ch.entry(x), ch.entry(y), width);
      };
      std::sort(order.begin(), order.end(), [&](int32_t x, int32_t y) {
        const int c = cmp(x, y);
        return c < 0 || (c == 0 && x < y);
      });
      canonical[s].resize(order.size());
      for (size_t i = 0; i < order.size(); ++i) {
        canonical[s][order[i]] = i > 0 && cmp(order[i - 1], order[i]) == 0
                                     ? canonical[s][order[i - 1]]
                                     : order[i];
      }
    }
    // Written vertices of one soup vertex are chained (a vertex has a few
    // corners): key w's entries are keys[w * n_seamed + s].
    std::vector<int32_t> first_written(soup.vertices.size(), -1), next;
    const std::vector<int32_t>& corners = soup.faces.indices();
    std::vector<int32_t> k(n_seamed);
    for (size_t c = 0; c < corners.size(); ++c) {
      for (size_t s = 0; s < n_seamed; ++s) {
        k[s] = canonical[s][seamed[s]->indices[c]];
      }
      int32_t w = first_written[corners[c]];
      while (w >= 0 &&
             !std::equal(k.begin(), k.end(), keys.begin() + w * n_seamed)) {
        w = next[w];
      }
      if (w < 0) {
        w = static_cast<int32_t>(source.size());
        source.push_back(corners[c]);
        keys.insert(keys.end(), k.begin(), k.end());
        next.push_back(first_written[corners[c]]);
        first_written[corners[c]] = w;
      }
      corner_vertex.push_back(w);
    }
    // Vertices on no face are written too (with each channel's first entry).
    for (size_t v = 0; v < soup.vertices.size(); ++v) {
      if (first_written[v] >= 0) continue;
      source.push_back(static_cast<int32_t>(v));
      keys.insert(keys.end(), n_seamed, 0);
    }
    if (source.size() > soup.vertices.size()) {
      notes->push_back(
          "PLY holds attributes per vertex: " +
          std::to_string(source.size() - soup.vertices.size()) +
          " vertices written twice or more where a seam meets them");
    }
  }
  out << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian")
      << " 1.0\nelement vertex " << source.size()
      << "\nproperty double x\nproperty double y\nproperty double z\n";
  for (const AttributeChannel& ch : soup.attributes) {
    const char* const* names = nullptr;
    static const char* kNormal[] = {"nx", "ny", "nz"};
    static const char* kColor[] = {"red", "green", "blue", "alpha"};
    static const char* kUv[] = {"s", "t"};
    if (ch.name == "normal" && ch.dims == 3) names = kNormal;
    if (ch.name == "uv" && ch.dims == 2) names = kUv;
    if (ch.name == "color" && (ch.dims == 3 || ch.dims == 4)) {
      for (int d = 0; d < ch.dims; ++d)
        out << "property uchar " << kColor[d] << '\n';
      continue;
    }
    for (int d = 0; d < ch.dims; ++d) {
      out << "property float "
          << (names          ? std::string(names[d])
              : ch.dims == 1 ? ch.name
                             : ch.name + "_" + std::to_string(d))
          << '\n';
    }
  }
  // Corner counts in a byte, as most tools write them, or in 16 bits when a
  // face needs it; a face of more corners than that is written as a fan.
  size_t largest = 0;
  for (FaceView f : soup.faces) largest = std::max(largest, f.size());
  const bool wide = largest > 255;
  constexpr size_t kMaxCorners = 65535;
  size_t faces = 0, fanned = 0;
  for (FaceView f : soup.faces) {
    faces += f.size() > kMaxCorners ? f.size() - 2 : 1;
    fanned += f.size() > kMaxCorners;
  }
  if (fanned > 0) {
    notes->push_back(std::to_string(fanned) + " faces of more than " +
                     std::to_string(kMaxCorners) +
                     " corners written as fans of triangles: PLY counts "
                     "corners in 16 bits at most");
  }
  out << "element face " << faces << "\nproperty list "
      << (wide ? "ushort" : "uchar") << " int vertex_indices\nend_header\n";
  auto put = [&](auto value) {
    if (ascii) {
      if constexpr (sizeof(value) == 1) {
        out << static_cast<int>(value);
      } else {
        out << value;
      }
    } else {
      PutLittleEndian(out, value);
    }
  };
  auto space = [&] {
    if (ascii) out << ' ';
  };
  size_t rounded = 0;  // colours that bytes do not hold exactly
  for (size_t w = 0; w < source.size(); ++w) {
    const Vec3& p = soup.vertices[source[w]];
    put(p.x), space(), put(p.y), space(), put(p.z);
    size_t s = 0;
    for (const AttributeChannel& ch : soup.attributes) {
      const int32_t e =
          ch.per_corner() ? keys[w * seamed.size() + s++] : source[w];
      for (int d = 0; d < ch.dims; ++d) {
        space();
        const float x = ch.entry(e)[d];
        if (ch.name == "color" && (ch.dims == 3 || ch.dims == 4)) {
          const auto byte =
              static_cast<uint8_t>(std::clamp(x, 0.0f, 1.0f) * 255.0f + 0.5f);
          rounded += std::abs(byte / 255.0f - x) > 1e-6f;
          put(byte);
        } else {
          const auto precision = out.precision(9);
          put(x);
          out.precision(precision);
        }
      }
    }
    if (ascii) out << '\n';
  }
  if (rounded > 0) {
    notes->push_back(std::to_string(rounded) +
                     " colour values written to the nearest of PLY's 256 "
                     "steps (clamped to [0, 1] where outside)");
  }
  auto put_count = [&](size_t n) {
    if (wide) {
      put(static_cast<uint16_t>(n));
    } else {
      put(static_cast<uint8_t>(n));
    }
  };
  size_t c = 0;
  for (FaceView f : soup.faces) {
    if (f.size() > kMaxCorners) {
      for (size_t k = 1; k + 1 < f.size(); ++k) {
        put_count(3);
        for (size_t j : {size_t{0}, k, k + 1})
          space(), put(corner_vertex[c + j]);
        if (ascii) out << '\n';
      }
      c += f.size();
      continue;
    }
    put_count(f.size());
    for (size_t k = 0; k < f.size(); ++k) space(), put(corner_vertex[c++]);
    if (ascii) out << '\n';
  }
}

}  // namespace dot
