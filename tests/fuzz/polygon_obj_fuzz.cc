// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: the OBJ polygon parser (dot::ReadPolygonObj: "v", "vn"
// and one "l" polyline). Oracle: never crash; a failure has a message; an
// accepted polygon has no normals or one per vertex, and every vertex (and
// normal) is one the file's "v" ("vn") lines gave.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "dot/io.h"

namespace {

bool SameBits(const dot::Vec3& a, const dot::Vec3& b) {
  return std::memcmp(&a, &b, sizeof(dot::Vec3)) == 0;
}

bool AmongBits(const dot::Vec3& p, const std::vector<dot::Vec3>& set) {
  for (const dot::Vec3& q : set) {
    if (SameBits(p, q)) return true;
  }
  return false;
}

// The "v" / "vn" values as the parser reads them, in file order.
void Collect(const std::string& text, std::vector<dot::Vec3>* v,
             std::vector<dot::Vec3>* vn) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    dot::Vec3 p;
    if (!(s >> tag) || (tag != "v" && tag != "vn")) continue;
    if (s >> p.x >> p.y >> p.z) (tag == "v" ? v : vn)->push_back(p);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  dot::PolygonData polygon;
  const dot::Status status = dot::ReadPolygonObj(in, &polygon);
  if (!status.ok()) {
    if (status.message.empty()) abort();
    return 0;
  }
  if (!polygon.normals.empty() &&
      polygon.normals.size() != polygon.vertices.size()) {
    abort();
  }
  std::vector<dot::Vec3> v, vn;
  Collect(text, &v, &vn);
  for (const dot::Vec3& p : polygon.vertices) {
    if (!AmongBits(p, v)) abort();
  }
  for (const dot::Vec3& n : polygon.normals) {
    if (!AmongBits(n, vn)) abort();
  }
  return 0;
}
