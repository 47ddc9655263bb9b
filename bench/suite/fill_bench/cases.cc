// SPDX-License-Identifier: AGPL-3.0-or-later
// The benchmark's meshes: libcgal-demo's open meshes, and holes cut into
// its closed ones (grown holes, pinched pairs, dendritic holes), each
// with its ground truth.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <random>
#include <unordered_map>
#include <unordered_set>

#include "fill_bench/fill_bench.h"
#include "mesh/edge_index.h"

namespace dot::bench::fill {
namespace {

// `name`.off in the mesh directory, extracted from libcgal-demo's tarball
// when missing. Empty when it cannot be had.
std::string MeshPath(const Config& config, const std::string& name) {
  const std::string path = config.mesh_dir + "/" + name + ".off";
  if (std::filesystem::exists(path)) return path;
  if (!std::filesystem::exists(kTarball)) return "";
  const std::string tmp = path + ".part";
  const std::string cmd = std::string("tar -xzOf ") + kTarball +
                          " data/meshes/" + name + ".off > '" + tmp +
                          "' 2>/dev/null";
  std::error_code ec;
  if (std::system(cmd.c_str()) != 0 ||
      std::filesystem::file_size(tmp, ec) == 0) {
    std::filesystem::remove(tmp, ec);
    return "";
  }
  std::filesystem::rename(tmp, path, ec);
  return ec ? "" : path;
}

// `pairs` pinched holes: a hole A grown with GrowHole (`ta` triangles) and a
// hole B of `tb` triangles grown from a face at one of A's boundary
// vertices v, never touching A elsewhere; so the border of A and B passes v
// twice (two fans of faces meet at v). Pairs share no vertex.
Status CutPinched(const MeshData& mesh, int pairs, int ta, int tb,
                  uint64_t seed, MeshData* holey, MeshData* removed) {
  const size_t nv = mesh.vertices.size(), nf = mesh.triangles.size();
  std::vector<std::vector<int32_t>> vertex_faces(nv);
  std::unordered_map<uint64_t, std::vector<int32_t>> edge_faces;
  for (size_t f = 0; f < nf; ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      vertex_faces[t[k]].push_back(static_cast<int32_t>(f));
      edge_faces[UndirectedEdgeKey(t[k], t[(k + 1) % 3])].push_back(
          static_cast<int32_t>(f));
    }
  }
  std::vector<bool> in_hole(nf, false), near(nv, false);
  std::mt19937_64 rng(seed);
  int made = 0;
  for (uint64_t attempt = 0; made < pairs && attempt < 200u * pairs;
       ++attempt) {
    Hole a;
    if (!GrowHole(mesh, ta, seed * 7919 + attempt, &a).ok()) continue;
    std::vector<bool> in_a(nf, false), va(nv, false);
    bool apart = true;
    for (int32_t f : a.removed) {
      in_a[f] = true;
      for (int32_t v : mesh.triangles[f]) apart &= !near[v], va[v] = true;
    }
    if (!apart) continue;
    std::vector<int32_t> rim;  // A's boundary vertices
    for (size_t v = 0; v < nv; ++v) {
      if (!va[v]) continue;
      for (int32_t f : vertex_faces[v]) {
        if (!in_a[f]) {
          rim.push_back(static_cast<int32_t>(v));
          break;
        }
      }
    }
    std::shuffle(rim.begin(), rim.end(), rng);
    std::vector<int32_t> b;
    for (int32_t v : rim) {
      for (int32_t f0 : vertex_faces[v]) {
        const Triangle& t0 = mesh.triangles[f0];
        bool ok = !in_a[f0] && !in_hole[f0];
        for (int32_t u : t0) ok &= u == v || (!va[u] && !near[u]);
        if (!ok) continue;
        // Grow B: a face across one of B's edges whose third vertex is new
        // (so B stays a disk with a simple boundary) and away from A.
        b = {f0};
        std::unordered_set<int32_t> in_b = {f0};
        std::unordered_set<int32_t> vb(t0.begin(), t0.end());
        while (static_cast<int>(b.size()) < tb) {
          std::vector<int32_t> next;
          for (int32_t f : b) {
            const Triangle& t = mesh.triangles[f];
            for (int k = 0; k < 3; ++k) {
              for (int32_t g :
                   edge_faces[UndirectedEdgeKey(t[k], t[(k + 1) % 3])]) {
                if (in_b.count(g) || in_a[g] || in_hole[g]) continue;
                int32_t third = -1;
                for (int32_t u : mesh.triangles[g]) {
                  if (u != t[k] && u != t[(k + 1) % 3]) third = u;
                }
                if (third < 0 || vb.count(third) || va[third] || near[third]) {
                  continue;
                }
                next.push_back(g);
              }
            }
          }
          if (next.empty()) break;
          const int32_t g = next[rng() % next.size()];
          b.push_back(g);
          in_b.insert(g);
          for (int32_t u : mesh.triangles[g]) vb.insert(u);
        }
        if (static_cast<int>(b.size()) == tb) break;
        b.clear();
      }
      if (!b.empty()) break;
    }
    if (b.empty()) continue;
    for (int32_t f : a.removed) in_hole[f] = true;
    for (int32_t f : b) in_hole[f] = true;
    for (size_t f = 0; f < nf; ++f) {
      if (!in_hole[f]) continue;
      for (int32_t v : mesh.triangles[f]) near[v] = true;
    }
    ++made;
  }
  if (made < pairs) {
    return InvalidArgument("room for only " + std::to_string(made) +
                           " pinched pairs");
  }
  std::vector<bool> kept(nf);
  for (size_t f = 0; f < nf; ++f) kept[f] = !in_hole[f];
  *holey = SubMesh(mesh, kept);
  *removed = SubMesh(mesh, in_hole);
  return OkStatus();
}

// A cut: holes of `triangles` triangles (CutHoles), or pinched pairs.
struct CutSpec {
  std::string kind;
  int count = 0, triangles = 0, small = 0;  // small: B of a pinched pair
  uint64_t seed = 1;
};

}  // namespace

bool Repaired(const PolygonSoup& soup, const std::string& what, MeshData* out) {
  RepairReport rr;
  const Status s = RepairMesh(soup, out, &rr);
  if (!s.ok()) {
    std::cerr << "dot-bench fill: " << what << ": " << s.message << "\n";
  }
  return s.ok();
}

bool LoadMesh(const Config& config, const std::string& name, MeshData* out) {
  const std::string path = MeshPath(config, name);
  PolygonSoup soup;
  if (path.empty() || !ReadPolygonSoupFile(path, &soup).ok()) {
    std::cerr << "dot-bench fill: cannot read mesh " << name << "\n";
    return false;
  }
  return Repaired(soup, name, out);
}

std::vector<Case> MakeCases(const Config& config) {
  std::vector<Case> cases;
  const std::vector<std::string> open =
      config.quick
          ? std::vector<std::string>{"elephant-with-holes", "holes"}
          : std::vector<std::string>{"elephant-with-holes", "holes", "lion",
                                     "mech-holes-shark", "head"};
  for (const std::string& name : open) {
    Case c;
    c.name = name;
    c.kind = "open";
    c.base = name;
    if (LoadMesh(config, name, &c.mesh)) cases.push_back(std::move(c));
  }
  struct Base {
    std::string name;
    std::vector<CutSpec> cuts;
  };
  std::vector<Base> bases;
  if (config.quick) {
    bases = {{"elephant", {{"cut", 4, 30, 0, 1}, {"pinched", 1, 60, 20, 4}}},
             {"armadillo", {{"cut", 2, 300, 0, 2}}}};
  } else {
    const std::vector<CutSpec> common = {{"cut", 10, 30, 0, 1},
                                         {"cut", 4, 300, 0, 2},
                                         {"cut", 2, 1500, 0, 3},
                                         {"pinched", 2, 120, 40, 4}};
    for (const char* name :
         {"elephant", "armadillo", "bunny00", "refined_elephant", "cow",
          "homer", "camel", "man"}) {
      bases.push_back({name, common});
    }
    // Large dendritic holes (non-Delaunay boundaries, CGAL's cubic
    // fallback) where the mesh has room for them.
    // 2,500 triangles removed leave boundaries of 350-600 vertices; on
    // the smaller meshes (elephant, homer, camel) most of them send CGAL to
    // its cubic search.
    for (Base& b : bases) {
      const bool small =
          b.name == "elephant" || b.name == "homer" || b.name == "camel";
      for (uint64_t seed : {5, 6, 7, 8}) {
        if (seed <= 6 || small)
          b.cuts.push_back({"dendritic", 1, 2500, 0, seed});
      }
    }
  }
  for (const Base& base : bases) {
    MeshData closed;
    if (!LoadMesh(config, base.name, &closed)) continue;
    std::vector<HoleLoop> loops;
    if (!FindHoleLoops(closed, &loops).ok() || !loops.empty()) {
      std::cerr << "dot-bench fill: " << base.name
                << " is not closed; not used\n";
      continue;
    }
    for (const CutSpec& cut : base.cuts) {
      Case c;
      c.kind = cut.kind;
      c.base = base.name;
      MeshData holey;
      Status s;
      if (cut.kind == "pinched") {
        c.name = base.name + "/pinch" + std::to_string(cut.count) + "-t" +
                 std::to_string(cut.triangles) + "+" +
                 std::to_string(cut.small) + "-s" + std::to_string(cut.seed);
        s = CutPinched(closed, cut.count, cut.triangles, cut.small, cut.seed,
                       &holey, &c.removed);
      } else {
        // Fewer holes when the mesh has no room for them all.
        int count = cut.count;
        do {
          s = CutHoles(closed, count, cut.triangles, cut.seed, &holey,
                       &c.removed);
        } while (!s.ok() && --count > 0);
        c.name = base.name + "/k" + std::to_string(count) + "-t" +
                 std::to_string(cut.triangles) + "-s" +
                 std::to_string(cut.seed);
      }
      if (!s.ok() || !Repaired(ToSoup(holey), c.name, &c.mesh)) {
        std::cerr << "dot-bench fill: " << c.name << ": " << s.message << "\n";
        continue;
      }
      c.original = closed;
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

}  // namespace dot::bench::fill
