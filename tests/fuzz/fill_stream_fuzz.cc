// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: a FillHoles request stream as dot-server reads it
// (server/rpc/fill_holes_reactor.cc): raw messages in any order and size,
// each parsed alone (a message that does not parse is refused by its
// position), fed to wire::FillRequestReader under small limits, the options
// translated, and the soup filled by dot::FillSoup (repair, or only
// triangulation with no_repair, then FillHoles) under a 100 ms deadline,
// as the server's FillHoles reactor does.
//
// Input framing: a sequence of [2-byte little-endian length][that many
// bytes] messages (a short last one takes what is left).
//
// Oracle (the service's honesty): never crash; every refusal is a non-OK
// status with a message and never gRPC OK; an OK fill has only finite
// vertices, keeps the repaired input's vertices first and unchanged, has
// faces over existing, distinct vertices, counts that add up, and a mesh
// reported closed has every edge on exactly two faces; attribute channels
// come back well formed and finite, with an entry for every corner; its
// patches in the ids as sent (PatchesAsSent, the patches answer) agree
// with the mesh and carry every channel at every corner.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "google/protobuf/stubs/logging.h"
#include "wire/fill_wire.h"
#include "wire/wire.h"
#include "wire_oracle.h"

namespace v1 = dot::v1;

namespace {

// Small meshes only: the fuzzer explores the protocol and the honesty of
// the answer, not the cost of big fills.
constexpr size_t kMaxVertices = 300;
constexpr size_t kMaxFaces = 600;

using dot::fuzz::Fail;

void CheckRefusal(const dot::Status& s) {
  dot::fuzz::CheckRefusal(s, /*no_triangulation_is_ok=*/false);
}

void CheckFill(const dot::MeshData& input, const dot::FillResult& r) {
  const dot::MeshData& m = r.mesh;
  if (m.vertices.size() < input.vertices.size()) Fail("input vertices lost");
  for (size_t v = 0; v < m.vertices.size(); ++v) {
    if (!dot::IsFinite(m.vertices[v])) {
      Fail("vertex " + std::to_string(v) + " is not finite");
    }
    if (v < input.vertices.size()) {
      const dot::Vec3 &a = m.vertices[v], &b = input.vertices[v];
      if (a.x != b.x || a.y != b.y || a.z != b.z) {
        Fail("input vertex " + std::to_string(v) + " moved");
      }
    }
  }
  const auto n = static_cast<int32_t>(m.vertices.size());
  std::map<std::pair<int32_t, int32_t>, int> edges;
  for (const dot::Triangle& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= n) Fail("face over a missing vertex");
      const int32_t a = t[k], b = t[(k + 1) % 3];
      if (a == b) Fail("face repeats a vertex");
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  const dot::FillReport& rep = r.report;
  if (rep.filled + rep.skipped + rep.unfilled + rep.listed + rep.stopped !=
          rep.loops ||
      static_cast<int32_t>(rep.holes.size()) != rep.loops) {
    Fail("hole counts do not add up");
  }
  if (rep.closed) {
    for (const auto& [edge, uses] : edges) {
      if (uses != 2) Fail("reported closed with an open or shared edge");
    }
  }
  if (m.triangles.empty()) Fail("OK with an empty mesh");
}

// The patches answer (FILL_ANSWER_PATCHES) of an OK fill: one per filled
// hole, new vertices numbered on from the soup's and equal to the fill's,
// faces over ids that exist, each replaced face a face of the soup.
void CheckPatches(const dot::PolygonSoup& soup, const dot::SoupFillResult& r,
                  const std::vector<dot::Vec3>& filled) {
  const auto sent = static_cast<int64_t>(soup.vertices.size());
  const auto patches = dot::PatchesAsSent(r, sent);
  if (static_cast<int32_t>(patches.size()) != r.fill.report.filled) {
    Fail("patches are not one per filled hole");
  }
  int64_t next = sent;
  for (const dot::SentPatch& p : patches) {
    if (p.first_vertex != next) Fail("patch vertices are not numbered on");
    for (size_t k = 0; k < p.new_vertices.size(); ++k) {
      const dot::Vec3& a = p.new_vertices[k];
      const dot::Vec3& b = filled[r.input_vertices + (next - sent) + k];
      if (!(a == b)) Fail("a patch vertex is not the fill's");
    }
    next += static_cast<int64_t>(p.new_vertices.size());
    auto check = [&](const dot::Triangle& t) {
      for (int32_t v : t) {
        if (v < 0 || v >= next) Fail("a patch face names no vertex");
      }
    };
    for (const dot::Triangle& t : p.faces) check(t);
    size_t pieces = 0;
    for (const auto& t : p.replacements) pieces += t.size();
    if (p.attributes.size() != r.soup.attributes.size()) {
      Fail("a patch does not carry every channel");
    }
    for (const dot::PatchChannel& c : p.attributes) {
      if (c.faces.size() != 3 * c.dims * p.faces.size() ||
          c.replaced.size() != 3 * c.dims * pieces) {
        Fail("a patch channel misses corners");
      }
    }
    for (size_t k = 0; k < p.replaced_faces.size(); ++k) {
      if (p.replaced_faces[k] < 0 ||
          p.replaced_faces[k] >= static_cast<int32_t>(soup.faces.size())) {
        Fail("a replaced face is not a face of the soup");
      }
      for (const dot::Triangle& t : p.replacements[k]) check(t);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);  // parse errors are expected
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dot::wire::FillRequestReader reader(kMaxVertices, kMaxFaces);
  size_t at = 0, messages = 0;
  while (at + 2 <= size) {
    const size_t length = std::min<size_t>(
        data[at] | static_cast<size_t>(data[at + 1]) << 8, size - at - 2);
    v1::FillHolesRequest m;
    if (!m.ParseFromArray(data + at + 2, static_cast<int>(length))) {
      return 0;  // refused by position, as the reactor does: nothing to fill
    }
    at += 2 + length;
    ++messages;
    const dot::Status s = reader.Add(m);
    if (!s.ok()) {
      CheckRefusal(s);
      return 0;
    }
  }
  if (messages == 0) return 0;
  dot::PolygonSoup soup;
  dot::Status s = reader.Finish(&soup);
  if (!s.ok()) {
    CheckRefusal(s);
    return 0;
  }
  dot::FillOptions options;
  s = dot::wire::FillOptionsFromWire(reader.options(), &options);
  if (!s.ok()) {
    CheckRefusal(s);
    return 0;
  }
  options.threads = 1;
  // Short: inputs that run into it (exact Delaunay predicates on
  // co-spherical rims, dense refinement) would otherwise take most of a
  // campaign's time; a stop is itself one of the outcomes under test.
  dot::Control control;
  control.deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
  // The server's use case itself; the repair is run again alone only for
  // the oracle (the input the fill must keep).
  const dot::SoupFillResult r = dot::FillSoup(soup, options, control);
  if (!r.fill.status.ok()) CheckRefusal(r.fill.status);
  // A stopped fill that kept its finished holes owes the same promise.
  if (!r.fill.status.ok() && !r.fill.partial) return 0;
  dot::MeshData mesh;
  dot::RepairReport repair;
  s = options.repair ? dot::RepairMesh(soup, &mesh, &repair)
                     : dot::TriangulateSoup(soup, &mesh);
  if (!s.ok()) Fail("FillSoup filled a soup its repair refuses");
  if (r.input_vertices != static_cast<int64_t>(mesh.vertices.size()) ||
      r.input_faces != static_cast<int64_t>(mesh.triangles.size())) {
    Fail("FillSoup's input counts are not the repaired mesh's");
  }
  // With channels (or polygons kept) the answer is the soup: its faces
  // as fans are what the mesh promise holds for.
  dot::FillResult answer = r.fill;
  if (!r.soup.faces.empty()) {
    if (!dot::CheckAttributes(r.soup).ok()) Fail("answered channels are bad");
    answer.mesh.vertices = r.soup.vertices;
    for (dot::FaceView f : r.soup.faces) {
      for (size_t k = 1; k + 1 < f.size(); ++k)
        answer.mesh.triangles.push_back({f[0], f[k], f[k + 1]});
    }
  }
  CheckFill(mesh, answer);
  // The patches answer is made only without keep_polygons (the server asks
  // for polygons with the mesh answer alone).
  if (!options.keep_polygons) CheckPatches(soup, r, answer.mesh.vertices);
  return 0;
}
