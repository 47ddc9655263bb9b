// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: the plain-text polygon parser (dot::ReadPolygonText,
// "x y z [nx ny nz]" per line, blank lines between loops). Oracle: never
// crash; a failure has a message; an accepted polygon has no normals or one
// per vertex, several loops of at least 3 vertices summing to the vertex
// count, and survives a round trip through WritePolygonText bit for bit.
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
  if (polygon.loop_sizes.size() == 1) abort();
  size_t total = 0;
  for (int32_t size : polygon.loop_sizes) {
    if (size < 3) abort();
    total += static_cast<size_t>(size);
  }
  if (!polygon.loop_sizes.empty() && total != polygon.vertices.size()) abort();
  // Round trip through the writer.
  std::ostringstream out;
  if (!dot::WritePolygonText(out, polygon).ok()) abort();
  std::istringstream again(out.str());
  dot::PolygonData reread;
  if (!dot::ReadPolygonText(again, &reread).ok()) abort();
  if (reread.vertices.size() != polygon.vertices.size() ||
      reread.normals.size() != polygon.normals.size() ||
      reread.loop_sizes != polygon.loop_sizes) {
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
