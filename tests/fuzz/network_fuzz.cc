// SPDX-License-Identifier: AGPL-3.0-or-later
// libFuzzer target: curve networks into surfaces. The last byte picks the
// input: an OBJ network file parsed by dot::ReadNetworkObj, or a small
// network decoded from the bytes (3 to 24 points on a small integer grid,
// so that curves meet, cross, overlap and repeat; 1 to 12 polylines,
// closed or not, sometimes normals, sometimes user cycles); then
// dot::SurfaceNetwork on one thread under a 200 ms deadline, at a stage
// the bytes pick.
//
// Oracle (the contract of dot/network.h, checked from the mesh alone):
//  - a failure is a known non-OK code with a message;
//  - an OK result keeps every input vertex first, in order, bit for bit,
//    has finite vertices only, triangles over existing and distinct
//    vertices, every curve edge of a network with every patch surfaced as
//    a mesh edge, no two faces crossing (exact predicates), and when it is
//    reported closed with no non-manifold curve, every edge on two faces
//    run opposite ways.
#include <fuzzer/FuzzedDataProvider.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dot/network.h"
#include "dot/validate.h"

namespace {

const dot::CurveNetwork* g_network = nullptr;
const dot::SurfaceOptions* g_options = nullptr;

// The input being surfaced: its options and the network as OBJ.
void PrintInput() {
  if (g_options != nullptr) {
    std::fprintf(
        stderr,
        "stage %s, skip_longest %d, islands %s, weld %g, %zu user cycles:\n",
        std::string(dot::FillStageName(g_options->stage)).c_str(),
        g_options->skip_longest ? 1 : 0,
        std::string(dot::NetworkIslandsName(g_options->islands)).c_str(),
        g_options->weld_distance, g_options->cycles.size());
    for (const auto& patch : g_options->cycles) {
      for (const auto& loop : patch) {
        std::fprintf(stderr, " |");
        for (int32_t v : loop) std::fprintf(stderr, " %d", v);
      }
      std::fprintf(stderr, "\n");
    }
  }
  if (g_network != nullptr) {
    std::ostringstream obj;
    (void)dot::WriteNetworkObj(obj, *g_network);
    std::fprintf(stderr, "network:\n%s", obj.str().c_str());
  }
}

[[noreturn]] void Fail(const char* what) {
  std::fprintf(stderr, "oracle failed: %s\n", what);
  PrintInput();
  abort();
}

dot::CurveNetwork Decode(FuzzedDataProvider* in, dot::SurfaceOptions* o) {
  dot::CurveNetwork net;
  const int points = in->ConsumeIntegralInRange(3, 24);
  for (int k = 0; k < points; ++k) {
    net.vertices.push_back(
        {static_cast<double>(in->ConsumeIntegralInRange(-3, 3)),
         static_cast<double>(in->ConsumeIntegralInRange(-3, 3)),
         static_cast<double>(in->ConsumeIntegralInRange(-3, 3))});
  }
  const int lines = in->ConsumeIntegralInRange(1, 12);
  for (int l = 0; l < lines; ++l) {
    std::vector<int32_t> line;
    const int length = in->ConsumeIntegralInRange(2, 8);
    for (int k = 0; k < length; ++k) {
      line.push_back(in->ConsumeIntegralInRange(0, points - 1));
    }
    if (in->ConsumeBool()) line.push_back(line.front());
    net.polylines.push_back(std::move(line));
  }
  if (in->ConsumeIntegralInRange(0, 7) == 0) {
    for (int k = 0; k < points; ++k) {
      net.normals.push_back(
          {static_cast<double>(in->ConsumeIntegralInRange(-1, 1)),
           static_cast<double>(in->ConsumeIntegralInRange(-1, 1)), 1.0});
    }
  }
  if (in->ConsumeIntegralInRange(0, 7) == 0) {
    const int patches = in->ConsumeIntegralInRange(1, 4);
    for (int p = 0; p < patches; ++p) {
      std::vector<std::vector<int32_t>> loops(
          static_cast<size_t>(in->ConsumeIntegralInRange(1, 2)));
      for (auto& loop : loops) {
        const int length = in->ConsumeIntegralInRange(1, 6);
        for (int k = 0; k < length; ++k) {
          loop.push_back(in->ConsumeIntegralInRange(-1, points));
        }
      }
      o->cycles.push_back(std::move(loops));
    }
  }
  o->skip_longest = in->ConsumeBool();
  o->islands =
      static_cast<dot::NetworkIslands>(in->ConsumeIntegralInRange(0, 2));
  // Last, so that older corpus inputs decode as they did (no weld).
  if (in->ConsumeIntegralInRange(0, 7) == 1) {
    // Between the grid's distances (1, 1.41, 1.73, 2, ...), not on them.
    o->weld_distance = 0.3 + 0.5 * in->ConsumeIntegralInRange(1, 4);
  }
  return net;
}

void CheckResult(const dot::CurveNetwork& net, const dot::SurfaceResult& r) {
  if (!r.status.ok()) {
    if (r.status.message.empty()) Fail("a failure without a message");
    switch (r.status.code) {
      case dot::StatusCode::kInvalidArgument:
      case dot::StatusCode::kDeadlineExceeded:
      case dot::StatusCode::kResourceExhausted:
      case dot::StatusCode::kCancelled:
      case dot::StatusCode::kNoTriangulation:
        return;
      default:
        Fail("an unexpected status code");
    }
  }
  const auto& m = r.mesh;
  if (m.vertices.size() < net.vertices.size()) Fail("input vertices lost");
  for (size_t i = 0; i < net.vertices.size(); ++i) {
    if (std::memcmp(&m.vertices[i], &net.vertices[i], sizeof(dot::Vec3))) {
      Fail("an input vertex moved");
    }
  }
  for (const dot::Vec3& p : m.vertices) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      Fail("a vertex is not finite");
    }
  }
  std::map<std::pair<int32_t, int32_t>, int> directed;
  std::set<std::pair<int32_t, int32_t>> edges;
  for (const dot::Triangle& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || static_cast<size_t>(t[k]) >= m.vertices.size()) {
        Fail("a triangle indexes no vertex");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      Fail("a triangle repeats a vertex");
    }
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      ++directed[{a, b}];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  if (r.report.failed == 0 && r.report.surfaced > 0 &&
      r.report.surfaced == static_cast<int32_t>(r.report.patches.size())) {
    std::set<int32_t> dangling(r.report.dangling.begin(),
                               r.report.dangling.end());
    for (size_t c = 0; c < r.report.curve_vertices.size(); ++c) {
      if (dangling.count(static_cast<int32_t>(c))) continue;
      bool used = false;
      for (const auto& patch : r.report.patches) {
        for (const auto& loop : patch.loops) {
          for (const dot::CurveUse& u : loop) {
            used = used || static_cast<size_t>(u.curve) == c;
          }
        }
      }
      const auto& vs = r.report.curve_vertices[c];
      for (size_t k = 0; used && k + 1 < vs.size(); ++k) {
        const int32_t a = r.vertex_of_input[vs[k]];
        const int32_t b = r.vertex_of_input[vs[k + 1]];
        if (!edges.count({std::min(a, b), std::max(a, b)})) {
          Fail("a curve edge of a surfaced patch is no mesh edge");
        }
      }
    }
  }
  if (dot::CountIntersectingPairs(m.vertices, m.triangles) != 0) {
    Fail("faces cross");
  }
  if (r.report.closed && r.report.non_manifold_curves == 0) {
    for (const auto& [e, n] : directed) {
      const auto back = directed.find({e.second, e.first});
      if (n != 1 || back == directed.end() || back->second != 1) {
        Fail("reported closed, but an edge is not on two opposite faces");
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  dot::SurfaceOptions options;
  options.threads = 1;
  dot::CurveNetwork net;
  if (in.ConsumeIntegralInRange(0, 3) == 0) {
    std::istringstream text(in.ConsumeRemainingBytesAsString());
    const dot::Status s = dot::ReadNetworkObj(text, &net);
    if (!s.ok()) {
      if (s.message.empty()) Fail("a parse failure without a message");
      return 0;
    }
    if (net.vertices.size() > 200 || net.polylines.size() > 64) return 0;
  } else {
    options.stage =
        static_cast<dot::FillStage>(in.ConsumeIntegralInRange(0, 2));
    net = Decode(&in, &options);
  }
  g_network = &net;
  g_options = &options;
  // A crash prints nothing: NETWORK_FUZZ_PRINT=1 prints every input first.
  if (std::getenv("NETWORK_FUZZ_PRINT") != nullptr) PrintInput();
  dot::Control control;
  control.deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  CheckResult(net, dot::SurfaceNetwork(net, options, control));
  g_network = nullptr;
  g_options = nullptr;
  return 0;
}
