// SPDX-License-Identifier: AGPL-3.0-or-later
// Reading and writing curve networks (dot/network.h): OBJ polylines and
// text blocks. Readers keep the file's numbering; BuildNetworkGraph welds.
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "dot/network.h"

namespace dot {
namespace {

std::string At(int lineno) { return "line " + std::to_string(lineno) + ": "; }

bool HasObjExtension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(c));
  return ext == "obj";
}

}  // namespace

Status ReadNetworkObj(std::istream& in, CurveNetwork* out) {
  *out = {};
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v" || tag == "vn") {
      Vec3 p;
      if (!(s >> p.x >> p.y >> p.z)) {
        return InvalidArgument(At(lineno) + "bad '" + tag +
                               "' line: expected three numbers");
      }
      (tag == "v" ? out->vertices : out->normals).push_back(p);
    } else if (tag == "l") {
      std::vector<int32_t> polyline;
      std::string tok;
      while (s >> tok) {
        char* end = nullptr;
        errno = 0;
        const long raw = std::strtol(tok.c_str(), &end, 10);
        const long count = static_cast<long>(out->vertices.size());
        const long idx = raw > 0 ? raw - 1 : count + raw;
        if (end == tok.c_str() || (*end != '\0' && *end != '/') || errno != 0 ||
            raw == 0 || idx < 0 || idx >= count) {
          return InvalidArgument(
              At(lineno) + "vertex index '" + tok + "' is not one of the " +
              std::to_string(count) + " vertices defined so far");
        }
        polyline.push_back(static_cast<int32_t>(idx));
      }
      if (polyline.size() < 2) {
        return InvalidArgument(At(lineno) +
                               "an 'l' line needs at least two vertices");
      }
      out->polylines.push_back(std::move(polyline));
    } else if (tag == "f") {
      return InvalidArgument(At(lineno) +
                             "an 'f' face: this is a mesh, not a curve "
                             "network (which has 'l' polylines)");
    }
  }
  if (!out->normals.empty() && out->normals.size() != out->vertices.size()) {
    return InvalidArgument(std::to_string(out->normals.size()) +
                           " 'vn' normals for " +
                           std::to_string(out->vertices.size()) +
                           " vertices: give one per vertex or none");
  }
  if (out->polylines.empty()) {
    return InvalidArgument("no 'l' polylines: a curve network has some");
  }
  return OkStatus();
}

Status ReadNetworkText(std::istream& in, CurveNetwork* out) {
  *out = {};
  std::vector<int32_t> current;
  int with_normals = -1;
  int start_line = 0;
  auto finish = [&]() -> Status {
    if (current.empty()) return OkStatus();
    if (current.size() < 2) {
      return InvalidArgument(At(start_line) +
                             "a polyline of one point (a blank line ends a "
                             "polyline; each needs at least two points)");
    }
    out->polylines.push_back(std::move(current));
    current.clear();
    return OkStatus();
  };
  std::string line;
  int lineno = 1;
  for (; std::getline(in, line); ++lineno) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) {
      const Status s = finish();
      if (!s.ok()) return s;
      continue;
    }
    if (line[first] == '#') continue;
    std::istringstream s(line);
    std::vector<double> x;
    double d;
    while (s >> d) x.push_back(d);
    std::string rest;
    if (!s.eof() && (s.clear(), s >> rest)) {
      return InvalidArgument(At(lineno) + "'" + rest + "' is not a number");
    }
    if (x.size() != 3 && x.size() != 6) {
      return InvalidArgument(At(lineno) +
                             "expected 3 (x y z) or 6 (x y z nx ny nz) "
                             "numbers, found " +
                             std::to_string(x.size()));
    }
    if (with_normals < 0) with_normals = x.size() == 6;
    if (with_normals != (x.size() == 6)) {
      return InvalidArgument(At(lineno) +
                             "some points have normals and some do not");
    }
    if (current.empty()) start_line = lineno;
    current.push_back(static_cast<int32_t>(out->vertices.size()));
    out->vertices.push_back({x[0], x[1], x[2]});
    if (x.size() == 6) out->normals.push_back({x[3], x[4], x[5]});
  }
  const Status s = finish();
  if (!s.ok()) return s;
  if (out->polylines.empty()) {
    return InvalidArgument("no polylines (blocks of 'x y z' lines)");
  }
  return OkStatus();
}

Status ReadNetworkFile(const std::string& path, CurveNetwork* out) {
  errno = 0;
  std::ifstream in(path);
  if (!in) {
    return InvalidArgument(
        "cannot open curve network file '" + path + "'" +
        (errno ? std::string(": ") + std::strerror(errno) : std::string()));
  }
  Status s = HasObjExtension(path) ? ReadNetworkObj(in, out)
                                   : ReadNetworkText(in, out);
  if (!s.ok()) s.message = path + ": " + s.message;
  return s;
}

Status WriteNetworkObj(std::ostream& out, const CurveNetwork& network) {
  out << std::setprecision(17);
  for (const Vec3& p : network.vertices) {
    out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  for (const Vec3& n : network.normals) {
    out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
  }
  for (const auto& polyline : network.polylines) {
    out << 'l';
    for (int32_t v : polyline) out << ' ' << v + 1;
    out << '\n';
  }
  if (!out) return MakeStatus(StatusCode::kInternal, "write failed");
  return OkStatus();
}

}  // namespace dot
