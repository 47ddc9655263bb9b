// SPDX-License-Identifier: AGPL-3.0-or-later
// FillSoup, the use case behind the FillHoles RPC and dotctl: the repair
// and the fill it runs are exactly RepairMesh then FillHoles; options out
// of range are refused by the core, before any work, naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "dot/dot.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

// A grid with a square hole, every vertex sent twice (the second copy
// used by the odd faces): a soup that needs its repair.
PolygonSoup DuplicatedSoup() {
  const MeshData m = testing::GridWithSquareHole(8, 3, 5);
  PolygonSoup soup{m.vertices, {}, {}};
  soup.vertices.insert(soup.vertices.end(), m.vertices.begin(),
                       m.vertices.end());
  const auto n = static_cast<int32_t>(m.vertices.size());
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const int32_t shift = f % 2 ? n : 0;
    const Triangle& t = m.triangles[f];
    soup.faces.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  }
  return soup;
}

TEST(FillSoupTest, RunsTheRepairThenFillHoles) {
  const PolygonSoup soup = DuplicatedSoup();
  MeshData repaired;
  RepairReport repair;
  ASSERT_TRUE(RepairMesh(soup, &repaired, &repair).ok());
  ASSERT_GT(repair.merged_vertices, 0);
  const FillResult direct = FillHoles(repaired);
  ASSERT_TRUE(direct.status.ok()) << direct.status.message;

  const SoupFillResult r = FillSoup(soup);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  EXPECT_EQ(r.repair.merged_vertices, repair.merged_vertices);
  EXPECT_EQ(r.input_vertices, static_cast<int64_t>(repaired.vertices.size()));
  EXPECT_EQ(r.input_faces, static_cast<int64_t>(repaired.triangles.size()));
  EXPECT_EQ(r.fill.report.filled, 1);
  EXPECT_EQ(r.fill.mesh.triangles, direct.mesh.triangles);
  EXPECT_EQ(r.fill.mesh.vertices.size(), direct.mesh.vertices.size());
  EXPECT_TRUE(r.fill.report.closed == direct.report.closed);
}

TEST(FillSoupTest, WithoutRepairTheSoupIsFilledAsSent) {
  FillOptions options;
  options.repair = false;
  const SoupFillResult r = FillSoup(DuplicatedSoup(), options);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  EXPECT_EQ(r.repair.merged_vertices, 0);
  // Unmerged, the grid falls apart along every edge between an odd and an
  // even face: many more loops than the one hole.
  EXPECT_GT(r.fill.report.loops, 1);
  EXPECT_EQ(r.input_vertices,
            static_cast<int64_t>(DuplicatedSoup().vertices.size()));
}

TEST(FillSoupTest, OptionsOutOfRangeAreRefusedBeforeAnyWork) {
  struct Case {
    const char* words;
    void (*set)(FillOptions*);
  };
  const Case cases[] = {
      {"density must be between 0.1 and 100",
       [](FillOptions* o) { o->density = 0.01; }},
      {"density must be between 0.1 and 100",
       [](FillOptions* o) { o->density = std::nan(""); }},
      {"fairing_continuity must be 0, 1 or 2",
       [](FillOptions* o) { o->fairing_continuity = 3; }},
      {"max_hole_diameter must be a finite number >= 0",
       [](FillOptions* o) { o->selection.max_diameter = -1; }},
      {"max_hole_edges must be >= 0",
       [](FillOptions* o) { o->selection.max_edges = -1; }},
      {"threads must be >= 0", [](FillOptions* o) { o->threads = -2; }},
      {"every metric weight is zero",
       [](FillOptions* o) { o->weights = MetricWeights{}; }},
      {"is not finite",
       [](FillOptions* o) { o->weights[Metric::kArea] = HUGE_VAL; }},
  };
  // An empty soup: had the options passed, the repair would refuse it.
  const PolygonSoup empty;
  for (const Case& c : cases) {
    FillOptions o;
    c.set(&o);
    const Status check = CheckFillOptions(o);
    EXPECT_EQ(check.code, StatusCode::kInvalidArgument) << c.words;
    EXPECT_NE(check.message.find(c.words), std::string::npos) << check.message;
    const SoupFillResult r = FillSoup(empty, o);
    EXPECT_EQ(r.fill.status.message, check.message);
    const FillResult direct =
        FillHoles(testing::GridWithSquareHole(8, 3, 5), o);
    EXPECT_EQ(direct.status.message, check.message);
  }
  EXPECT_TRUE(CheckFillOptions(FillOptions{}).ok());
}

// The soup as the client keeps it, with the patches added: new vertices
// appended (checked to be numbered on), replaced faces swapped for their
// replacements, patch faces appended.
PolygonSoup ApplyPatches(const PolygonSoup& soup,
                         const std::vector<SentPatch>& patches) {
  PolygonSoup out = soup;
  std::map<int32_t, std::vector<Triangle>> replaced;
  for (const SentPatch& p : patches) {
    EXPECT_EQ(p.first_vertex, static_cast<int32_t>(out.vertices.size()));
    out.vertices.insert(out.vertices.end(), p.new_vertices.begin(),
                        p.new_vertices.end());
    for (size_t k = 0; k < p.replaced_faces.size(); ++k) {
      replaced[p.replaced_faces[k]] = p.replacements[k];
    }
  }
  out.faces.clear();
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    if (!replaced.count(static_cast<int32_t>(f))) {
      out.faces.push_back(soup.faces[f]);
    }
  }
  auto add = [&](const Triangle& t) {
    out.faces.push_back({t[0], t[1], t[2]});
  };
  for (const auto& [face, triangles] : replaced) {
    for (const Triangle& t : triangles) add(t);
  }
  for (const SentPatch& p : patches) {
    for (const Triangle& t : p.faces) add(t);
  }
  return out;
}

// Triangles as a sorted list, each rotated to start at its smallest id:
// the same faces in any order.
std::vector<Triangle> Canonical(std::vector<Triangle> faces) {
  for (Triangle& t : faces) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

// The oracle: the sent soup with the patches applied, repaired as the
// server repaired the original, is the mesh of the whole-mesh answer.
void ExpectPatchesRebuildTheFill(const PolygonSoup& soup,
                                 const FillOptions& options, const char* name) {
  const SoupFillResult r = FillSoup(soup, options);
  ASSERT_TRUE(r.fill.status.ok()) << name << ": " << r.fill.status.message;
  ASSERT_GT(r.fill.report.filled, 0) << name;
  const auto patches =
      PatchesAsSent(r, static_cast<int64_t>(soup.vertices.size()));
  EXPECT_EQ(patches.size(), static_cast<size_t>(r.fill.report.filled)) << name;
  // Every patch triangle, in the fill's ids, is a triangle of the filled
  // mesh with the same orientation (the repair below would hide a flip).
  std::vector<Triangle> filled = Canonical(r.fill.mesh.triangles);
  const auto sent = static_cast<int32_t>(soup.vertices.size());
  auto in_fill = [&](Triangle t) {
    for (int32_t& v : t) {
      v = v >= sent ? static_cast<int32_t>(r.input_vertices) + v - sent
          : r.repair.vertex_map.empty() ? v
                                        : r.repair.vertex_map[v];
    }
    return std::binary_search(filled.begin(), filled.end(), Canonical({t})[0]);
  };
  for (const SentPatch& p : patches) {
    for (const Triangle& t : p.faces) EXPECT_TRUE(in_fill(t)) << name;
    for (const auto& pieces : p.replacements) {
      for (const Triangle& t : pieces) EXPECT_TRUE(in_fill(t)) << name;
    }
  }
  MeshData rebuilt;
  RepairReport repair;
  ASSERT_TRUE(RepairMesh(ApplyPatches(soup, patches), &rebuilt, &repair).ok())
      << name;
  ASSERT_EQ(rebuilt.vertices.size(), r.fill.mesh.vertices.size()) << name;
  for (size_t v = 0; v < rebuilt.vertices.size(); ++v) {
    ASSERT_EQ(rebuilt.vertices[v], r.fill.mesh.vertices[v]) << name << " " << v;
  }
  EXPECT_EQ(Canonical(rebuilt.triangles), Canonical(r.fill.mesh.triangles))
      << name;
}

TEST(FillSoupTest, PatchesInTheSentIdsRebuildTheFilledMesh) {
  // Merged duplicates: patch faces name each vertex by its first copy.
  ExpectPatchesRebuildTheFill(DuplicatedSoup(), {}, "duplicated grid");
  // Edge protection splits faces next to the shark's holes: each comes
  // back as a replaced face, quads of the file's soup included.
  const std::string path = testing::MeshPath("mech-holes-shark.off");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " missing";
  PolygonSoup shark;
  ASSERT_TRUE(ReadPolygonSoupFile(path, &shark).ok());
  FillOptions o;
  o.stage = FillStage::kTriangulate;
  const SoupFillResult r = FillSoup(shark, o);
  size_t replaced = 0;
  for (const SentPatch& p :
       PatchesAsSent(r, static_cast<int64_t>(shark.vertices.size()))) {
    replaced += p.replaced_faces.size();
  }
  EXPECT_GT(replaced, 0u);
  ExpectPatchesRebuildTheFill(shark, o, "shark");
}

// A quad whose two triangles two holes split: the quad is replaced once,
// by the later patch, with both holes' pieces; the earlier patch names no
// vertex that comes after its own (a client adds patches in order).
TEST(FillSoupTest, APolygonTwoHolesSplitIsReplacedOnceByTheLaterPatch) {
  SoupFillResult r;
  r.input_vertices = 4;
  r.input_faces = 2;
  r.repair.face_origin = {0, 0};  // both triangles come from soup face 0
  r.fill.mesh.vertices = {{0, 0, 0}, {1, 0, 0},  {1, 1, 0},
                          {0, 1, 0}, {.5, 0, 0}, {.5, 1, 0}};
  // As FillHoles merges: each split face's first piece in its place, its
  // other pieces, then the hole's patch.
  r.fill.mesh.triangles = {{0, 4, 2}, {0, 2, 5}, {4, 1, 2},
                           {4, 1, 9}, {5, 2, 3}, {5, 3, 8}};
  FilledHole first{0, 4, {{{.5, 0, 0}}, {{4, 1, 9}}, {0}, {}}};
  first.patch.pieces = {{{0, 4, 2}, {4, 1, 2}}};
  FilledHole second{1, 5, {{{.5, 1, 0}}, {{5, 3, 8}}, {1}, {}}};
  second.patch.pieces = {{{0, 2, 5}, {5, 2, 3}}};
  r.fill.patches = {first, second};
  const auto patches = PatchesAsSent(r, 4);
  ASSERT_EQ(patches.size(), 2u);
  EXPECT_TRUE(patches[0].replaced_faces.empty());
  ASSERT_EQ(patches[1].replaced_faces, std::vector<int32_t>{0});
  EXPECT_EQ(Canonical(patches[1].replacements[0]),
            Canonical({{0, 4, 2}, {4, 1, 2}, {0, 2, 5}, {5, 2, 3}}));
  EXPECT_EQ(patches[0].first_vertex, 4);
  EXPECT_EQ(patches[1].first_vertex, 5);
}

TEST(FillSoupTest, LoopsThroughAVertexFillExactlyThoseLoops) {
  const MeshData torus = testing::HoleyTorus(60, 30, 3, 40);
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(torus, &loops).ok());
  ASSERT_EQ(loops.size(), 3u);
  FillOptions o;
  o.stage = FillStage::kTriangulate;
  o.selection.through_vertices = {loops[1].vertices[3]};
  const PolygonSoup soup = ToSoup(torus);
  const SoupFillResult r = FillSoup(soup, o);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_EQ(r.fill.report.holes.size(), 3u);
  for (const HoleReport& h : r.fill.report.holes) {
    EXPECT_EQ(h.status, h.id == 1 ? HoleStatus::kFilled : HoleStatus::kSkipped)
        << h.id << ": " << h.reason;
    if (h.id != 1) {
      EXPECT_EQ(h.reason, "through none of the requested vertices");
    }
  }
  // Two named loops, one vertex each; duplicates are harmless.
  o.selection.through_vertices = {loops[0].vertices[0], loops[2].vertices[5],
                                  loops[2].vertices[6]};
  EXPECT_EQ(FillSoup(soup, o).fill.report.filled, 2);
  // A vertex on no border, and one that is not in the mesh, are named.
  o.selection.through_vertices = {0};
  const bool zero_on_border =
      std::any_of(loops.begin(), loops.end(), [](const HoleLoop& l) {
        return std::count(l.vertices.begin(), l.vertices.end(), 0) > 0;
      });
  ASSERT_FALSE(zero_on_border);
  Status s = FillSoup(soup, o).fill.status;
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("vertex 0 is on no border loop"), std::string::npos)
      << s.message;
  o.selection.through_vertices = {static_cast<int32_t>(soup.vertices.size())};
  s = FillSoup(soup, o).fill.status;
  EXPECT_NE(s.message.find("is not a vertex of the mesh"), std::string::npos)
      << s.message;
}

TEST(FillSoupTest, LoopsThroughASecondCopyNameItsMergedVertex) {
  const PolygonSoup soup = DuplicatedSoup();
  const auto n = static_cast<int32_t>(soup.vertices.size() / 2);
  // Grid vertex (3, 3) is on the square hole's rim; name its second copy.
  FillOptions o;
  o.selection.through_vertices = {n + 3 * 9 + 3};
  const SoupFillResult r = FillSoup(soup, o);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  EXPECT_EQ(r.fill.report.filled, 1);
  // A second copy on no border is named as it was sent, not as repaired.
  o.selection.through_vertices = {n + 1 * 9 + 1};  // grid vertex (1, 1)
  const Status s = FillSoup(soup, o).fill.status;
  EXPECT_NE(s.message.find("loops_through: vertex " + std::to_string(n + 10) +
                           " is on no border loop"),
            std::string::npos)
      << s.message;
}

}  // namespace
}  // namespace dot
