// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: the mesh readers (dot::ReadPolygonSoupFile, CGAL 5.5's
// polygon-soup I/O for OFF, OBJ, PLY and STL, ASCII and binary), then
// repair (dot::RepairMesh), as `dotctl fill-holes` runs them. The first
// byte picks the format; the rest is the file. Oracle: never crash; a
// failure has a message; an accepted soup has only finite vertices and
// face indices in range; a repaired mesh's triangles index its vertices.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "dot/io.h"
#include "dot/mesh_repair.h"

namespace {

[[noreturn]] void Fail(const char* what) {
  std::fprintf(stderr, "mesh_file_fuzz oracle: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".off", ".obj", ".ply", ".stl"};
  const std::string path = "/tmp/dot-mesh-fuzz-" + std::to_string(::getpid()) +
                           kExtensions[data[0] % 4];
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1),
              static_cast<std::streamsize>(size - 1));
  }
  dot::PolygonSoup soup;
  const dot::Status read = dot::ReadPolygonSoupFile(path, &soup);
  ::unlink(path.c_str());
  if (!read.ok()) {
    if (read.message.empty()) Fail("a read failure without a message");
    return 0;
  }
  for (const dot::Vec3& p : soup.vertices) {
    if (!dot::IsFinite(p)) Fail("a non-finite vertex accepted");
  }
  for (const auto& face : soup.faces) {
    for (int32_t v : face) {
      if (v < 0 || static_cast<size_t>(v) >= soup.vertices.size()) {
        Fail("a face index out of range accepted");
      }
    }
  }
  if (soup.vertices.size() > 4096 || soup.faces.size() > 4096) return 0;
  dot::MeshData mesh;
  dot::RepairReport report;
  const dot::Status repaired = dot::RepairMesh(soup, &mesh, &report);
  if (!repaired.ok()) {
    if (repaired.message.empty()) Fail("a repair failure without a message");
    return 0;
  }
  for (const dot::Triangle& t : mesh.triangles) {
    for (int32_t v : t) {
      if (v < 0 || static_cast<size_t>(v) >= mesh.vertices.size()) {
        Fail("a repaired triangle indexes no vertex");
      }
    }
  }
  return 0;
}
