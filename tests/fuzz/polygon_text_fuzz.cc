// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: the plain-text polygon parser (dot::ReadPolygonText,
// "x y z [nx ny nz]" per line). Oracle: never crash; a failure has a
// message; an accepted polygon has no normals or one per vertex, and
// survives a round trip through its text form (17 digits) bit for bit.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

#include "dot/io.h"

namespace {

bool SameBits(const dot::Vec3& a, const dot::Vec3& b) {
  return std::memcmp(&a, &b, sizeof(dot::Vec3)) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  dot::PolygonData polygon;
  const dot::Status status = dot::ReadPolygonText(in, &polygon);
  if (!status.ok()) {
    if (status.message.empty()) abort();
    return 0;
  }
  if (!polygon.normals.empty() &&
      polygon.normals.size() != polygon.vertices.size()) {
    abort();
  }
  // Round trip, as WritePolygonText writes it.
  std::ostringstream out;
  out.precision(17);
  for (size_t i = 0; i < polygon.vertices.size(); ++i) {
    const dot::Vec3& p = polygon.vertices[i];
    out << p.x << ' ' << p.y << ' ' << p.z;
    if (!polygon.normals.empty()) {
      const dot::Vec3& n = polygon.normals[i];
      out << ' ' << n.x << ' ' << n.y << ' ' << n.z;
    }
    out << '\n';
  }
  std::istringstream again(out.str());
  dot::PolygonData reread;
  if (!dot::ReadPolygonText(again, &reread).ok()) abort();
  if (reread.vertices.size() != polygon.vertices.size() ||
      reread.normals.size() != polygon.normals.size()) {
    abort();
  }
  for (size_t i = 0; i < polygon.vertices.size(); ++i) {
    if (!SameBits(reread.vertices[i], polygon.vertices[i])) abort();
  }
  for (size_t i = 0; i < polygon.normals.size(); ++i) {
    if (!SameBits(reread.normals[i], polygon.normals[i])) abort();
  }
  return 0;
}
