// SPDX-License-Identifier: AGPL-3.0-or-later
// OBJ meshes with their attributes (mesh_formats.h).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <ostream>

#include "mesh_io/mesh_formats.h"

namespace dot {
namespace {

// Reads up to `max` numbers from `*p`; returns how many.
int Numbers(const char** p, double* out, int max) {
  int n = 0;
  while (n < max) {
    char* end = nullptr;
    const double x = std::strtod(*p, &end);
    if (end == *p) break;
    out[n++] = x;
    *p = end;
  }
  return n;
}

bool Blank(const char* p) {
  while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
  return *p == '\0' || *p == '#';
}

const AttributeChannel* Find(const PolygonSoup& soup, const char* name) {
  for (const AttributeChannel& ch : soup.attributes) {
    if (ch.name == name) return &ch;
  }
  return nullptr;
}

}  // namespace

Status ReadObjMesh(const std::string& path, PolygonSoup* out,
                   std::vector<std::string>* notes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return InvalidArgument("cannot open mesh file '" + path + "'");
  std::vector<float> colors, uvs, normals;
  std::vector<int32_t> uv_of, normal_of;  // per corner, -1: none
  size_t colored = 0, line_no = 0;
  bool materials = false, lines = false;
  std::string line;
  std::vector<int32_t> face;
  auto at = [&](const std::string& what) {
    return InvalidArgument("'" + path + "' line " + std::to_string(line_no) +
                           ": " + what);
  };
  while (std::getline(in, line)) {
    ++line_no;
    const char* p = line.c_str();
    while (*p == ' ' || *p == '\t') ++p;
    if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
      p += 2;
      double x[7];
      const int n = Numbers(&p, x, 7);
      if ((n != 3 && n != 4 && n != 6 && n != 7) || !Blank(p)) {
        return at("a vertex needs x y z (then w, or r g b)");
      }
      for (int k = 0; k < n; ++k) {
        if (!std::isfinite(x[k])) {
          return at(k < 3 ? "a coordinate is not finite"
                          : "a colour value is not finite");
        }
        if (k >= 3 && !std::isfinite(static_cast<float>(x[k]))) {
          return at("a colour value is beyond single precision");
        }
      }
      out->vertices.push_back({x[0], x[1], x[2]});
      if (n >= 6) {
        colors.resize(3 * (out->vertices.size() - 1), 1.0f);
        for (int k = n - 3; k < n; ++k)
          colors.push_back(static_cast<float>(x[k]));
        ++colored;
      }
    } else if (p[0] == 'v' && p[1] == 't' && (p[2] == ' ' || p[2] == '\t')) {
      p += 3;
      double x[3];
      const int n = Numbers(&p, x, 3);
      if (n < 1 || !Blank(p)) return at("a texture coordinate needs u [v [w]]");
      for (int k = 0; k < std::min(n, 2); ++k) {
        if (!std::isfinite(static_cast<float>(x[k]))) {
          return at(
              "a texture coordinate is not finite in single precision "
              "(attributes are floats)");
        }
      }
      uvs.push_back(static_cast<float>(x[0]));
      uvs.push_back(static_cast<float>(n > 1 ? x[1] : 0.0));
    } else if (p[0] == 'v' && p[1] == 'n' && (p[2] == ' ' || p[2] == '\t')) {
      p += 3;
      double x[3];
      if (Numbers(&p, x, 3) != 3 || !Blank(p))
        return at("a normal needs x y z");
      for (double c : x) {
        if (!std::isfinite(static_cast<float>(c))) {
          return at(
              "a normal is not finite in single precision (attributes "
              "are floats)");
        }
      }
      for (double c : x) normals.push_back(static_cast<float>(c));
    } else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
      p += 2;
      face.clear();
      while (!Blank(p)) {
        long idx[3] = {0, 0, 0};
        for (int part = 0; part < 3; ++part) {
          char* end = nullptr;
          if (*p != '/') {
            errno = 0;
            idx[part] = std::strtol(p, &end, 10);
            if (end == p || errno != 0) {
              return at("face corner " + std::to_string(face.size()) +
                        " is not a vertex index");
            }
            p = end;
          }
          if (*p != '/') break;
          ++p;
        }
        const size_t counts[3] = {out->vertices.size(), uvs.size() / 2,
                                  normals.size() / 3};
        const char* what[3] = {"vertex", "texture coordinate", "normal"};
        int32_t ids[3] = {-1, -1, -1};
        for (int part = 0; part < 3; ++part) {
          if (idx[part] == 0 && part > 0) continue;
          const long i = idx[part] > 0
                             ? idx[part] - 1
                             : static_cast<long>(counts[part]) + idx[part];
          if (idx[part] == 0 || i < 0 || i >= static_cast<long>(counts[part])) {
            return at("face corner " + std::to_string(face.size()) + " names " +
                      what[part] + " " + std::to_string(idx[part]) + " of " +
                      std::to_string(counts[part]));
          }
          ids[part] = static_cast<int32_t>(i);
        }
        face.push_back(ids[0]);
        uv_of.push_back(ids[1]);
        normal_of.push_back(ids[2]);
        while (*p == ' ' || *p == '\t') ++p;
      }
      if (face.size() < 3) {
        return at("a face needs at least 3 corners; it has " +
                  std::to_string(face.size()));
      }
      out->faces.Add(face.begin(), face.end());
    } else if (std::strncmp(p, "usemtl", 6) == 0 ||
               std::strncmp(p, "mtllib", 6) == 0) {
      materials = true;
    } else if (p[0] == 'l' && (p[1] == ' ' || p[1] == '\t')) {
      lines = true;
    }
  }
  if (in.bad()) return InvalidArgument("cannot read mesh file '" + path + "'");
  if (colored > 0) {
    // Some exporters write colours as 0..255: scaled when any exceeds 1.
    const float top = *std::max_element(colors.begin(), colors.end());
    if (top > 1 && top <= 255) {
      for (float& c : colors) c /= 255;
      if (notes != nullptr) {
        notes->push_back("'" + path +
                         "': vertex colours read as 0..255 (one "
                         "exceeds 1) and scaled to [0, 1]");
      }
    }
    if (colored == out->vertices.size()) {
      out->attributes.push_back({"color", 3, std::move(colors), {}});
    } else if (notes != nullptr) {
      notes->push_back(
          "'" + path + "': vertex colours dropped: " + std::to_string(colored) +
          " of " + std::to_string(out->vertices.size()) + " vertices have one");
    }
  }
  // A per-corner channel when every corner names an entry.
  auto corner_channel = [&](const char* name, int dims, std::vector<float>* v,
                            std::vector<int32_t>* of) {
    if (v->empty()) return;
    size_t named = 0;
    for (int32_t e : *of) named += e >= 0;
    if (named == of->size() && !of->empty()) {
      out->attributes.push_back({name, dims, std::move(*v), std::move(*of)});
    } else if (notes != nullptr) {
      notes->push_back("'" + path + "': " + name +
                       " dropped: " + std::to_string(named) + " of " +
                       std::to_string(of->size()) + " face corners name one");
    }
  };
  corner_channel("uv", 2, &uvs, &uv_of);
  corner_channel("normal", 3, &normals, &normal_of);
  if (notes != nullptr && materials) {
    notes->push_back("'" + path +
                     "': materials (usemtl, mtllib) are not kept: the "
                     "output has none");
  }
  if (notes != nullptr && lines) {
    notes->push_back("'" + path + "': polylines (l lines) are skipped");
  }
  return OkStatus();
}

void WriteObjSoup(std::ostream& out, const PolygonSoup& soup,
                  std::vector<std::string>* notes) {
  const AttributeChannel* color = Find(soup, "color");
  const AttributeChannel* const color_channel = color;
  const AttributeChannel* uv = Find(soup, "uv");
  const AttributeChannel* normal = Find(soup, "normal");
  if (color != nullptr && (color->per_corner() || color->dims < 3)) {
    notes->push_back(color->per_corner()
                         ? "attribute 'color' not written: OBJ holds colours "
                           "per vertex, and this one has a seam (PLY keeps it)"
                         : "attribute 'color' not written: it is not RGB");
    color = nullptr;
  }
  if (color != nullptr && color->dims > 3) {
    notes->push_back(
        "the alpha of attribute 'color' is not written: OBJ "
        "holds RGB (PLY keeps it)");
  }
  if (uv != nullptr && uv->dims != 2) uv = nullptr;
  if (normal != nullptr && normal->dims != 3) normal = nullptr;
  for (const AttributeChannel& ch : soup.attributes) {
    if (&ch != color_channel && &ch != uv && &ch != normal) {
      notes->push_back("attribute '" + ch.name +
                       "' not written: OBJ has no "
                       "place for it (PLY keeps it)");
    }
  }
  for (size_t v = 0; v < soup.vertices.size(); ++v) {
    const Vec3& p = soup.vertices[v];
    out << "v " << p.x << ' ' << p.y << ' ' << p.z;
    if (color != nullptr) {  // floats: every digit, not a double's 17
      const float* c = color->entry(v);
      const auto coordinates = out.precision(9);
      out << ' ' << c[0] << ' ' << c[1] << ' ' << c[2];
      out.precision(coordinates);
    }
    out << '\n';
  }
  const auto old_precision = out.precision(9);  // floats: every digit
  if (uv != nullptr) {
    for (size_t e = 0; e < uv->entries(); ++e)
      out << "vt " << uv->entry(e)[0] << ' ' << uv->entry(e)[1] << '\n';
  }
  if (normal != nullptr) {
    for (size_t e = 0; e < normal->entries(); ++e) {
      const float* n = normal->entry(e);
      out << "vn " << n[0] << ' ' << n[1] << ' ' << n[2] << '\n';
    }
  }
  out.precision(old_precision);
  auto entry = [](const AttributeChannel* ch, size_t corner, int32_t v) {
    return (ch->per_corner() ? ch->indices[corner] : v) + 1;
  };
  size_t corner = 0;
  for (FaceView f : soup.faces) {
    out << 'f';
    for (int32_t v : f) {
      out << ' ' << v + 1;
      if (uv != nullptr || normal != nullptr) {
        out << '/';
        if (uv != nullptr) out << entry(uv, corner, v);
        if (normal != nullptr) out << '/' << entry(normal, corner, v);
      }
      ++corner;
    }
    out << '\n';
  }
}

}  // namespace dot
