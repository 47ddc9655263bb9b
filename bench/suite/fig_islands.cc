// SPDX-License-Identifier: AGPL-3.0-or-later
// Holes with islands (issue 19): ring-shaped holes cut around islands into
// closed libcgal-demo meshes (CutIslandHoles), filled by FillHoles with its
// defaults (islands joined automatically). Each output is judged against
// the closed mesh it was cut from, outside the timing: every hole filled by
// one patch joining its island, closed, one piece with the closed mesh's
// Euler characteristic (its genus), no intersecting pair with a new face
// (exact predicates), distance to the removed surface. The same meshes with
// islands off show what filling each loop alone gives.
#include <iostream>

#include "fill_bench/fill_bench.h"
#include "measure.h"
#include "mesh/edge_index.h"
#include "suite.h"
#include "util/union_find.h"

namespace dot::bench {
namespace {

struct Cut {
  int count, triangles, island;
  uint64_t seed;
};

struct Row {
  std::string name;
  int rings = 0, joined = 0, filled_off = 0;
  int joined_allowed = 0;  // with allow_input_intersections
  Sample s;
  bool closed = false, one_piece = false, genus = false;
  int64_t pieces_off = 0;
  fill::Verdict v;
};

}  // namespace

int RunIslands(const Config& config, std::ostream& report) {
  const std::vector<std::string> meshes =
      config.quick ? std::vector<std::string>{"elephant", "armadillo"}
                   : std::vector<std::string>{
                         "elephant", "armadillo", "bunny00", "refined_elephant",
                         "cow",      "homer",     "camel",   "man"};
  const std::vector<Cut> cuts = {{3, 150, 30, 11}, {2, 600, 120, 12}};
  std::vector<Row> rows;
  int invalid = 0;
  for (const std::string& name : meshes) {
    MeshData closed;
    if (!fill::LoadMesh(config, name, &closed)) continue;
    for (const Cut& cut : cuts) {
      fill::Case c;
      c.kind = "island";
      c.base = name;
      c.name = name + "/k" + std::to_string(cut.count) + "-t" +
               std::to_string(cut.triangles) + "-i" +
               std::to_string(cut.island);
      if (!CutIslandHoles(closed, cut.count, cut.triangles, cut.island,
                          cut.seed, &c.mesh, &c.removed)
               .ok()) {
        std::cerr << "islands: " << c.name << ": no room\n";
        continue;
      }
      c.original = closed;
      std::cerr << "islands: " << c.name << "\n";
      Row row;
      row.name = c.name;
      row.rings = cut.count;
      FillResult r;
      row.s = Measure(config.reps, config.long_run_s, config.cap_s,
                      [&] { r = FillHoles(c.mesh); });
      if (!r.status.ok()) {
        std::cerr << "islands: " << c.name << ": " << r.status.message << "\n";
        ++invalid;
        continue;
      }
      for (const HoleReport& h : r.report.holes) {
        row.joined += !h.joined.empty() && h.status == HoleStatus::kFilled;
        if (h.status != HoleStatus::kFilled) {
          std::cerr << "islands:   hole " << h.id << " open: " << h.reason
                    << "\n";
        }
      }
      const auto judge = fill::MakeJudge(c);
      row.v = fill::Evaluate(*judge, r.mesh.vertices, r.mesh.triangles);
      row.closed = r.report.closed && row.v.closed;
      const MeshShape shape = ShapeOf(r.mesh);
      row.one_piece = shape.pieces == 1;
      row.genus = shape.euler == ShapeOf(closed).euler;
      if (row.v.pairs != 0 || row.v.non_manifold || row.v.misoriented ||
          r.report.closed != row.v.closed) {
        std::cerr << "islands: DEFECT " << c.name << "\n";
        ++invalid;
      }
      // Rings left open on a mesh that crosses itself near them: the
      // opt-in, judged for its topology (its crossings are reported).
      row.joined_allowed = row.joined;
      if (row.joined < row.rings) {
        FillOptions allow;
        allow.allow_input_intersections = true;
        const FillResult a = FillHoles(c.mesh, allow);
        row.joined_allowed = 0;
        for (const HoleReport& h : a.report.holes) {
          row.joined_allowed +=
              !h.joined.empty() && h.status == HoleStatus::kFilled;
        }
        const fill::Verdict va =
            fill::Evaluate(*judge, a.mesh.vertices, a.mesh.triangles);
        if (va.non_manifold || va.misoriented) {
          std::cerr << "islands: DEFECT (allow_input_intersections) " << c.name
                    << "\n";
          ++invalid;
        }
      }
      FillOptions off;
      off.islands = IslandMode::kOff;
      const FillResult alone = FillHoles(c.mesh, off);
      row.filled_off = alone.report.filled;
      row.pieces_off = ShapeOf(alone.mesh).pieces;
      rows.push_back(std::move(row));
    }
  }
  int rings = 0, joined = 0, whole = 0, allowed = 0;
  for (const Row& r : rows) {
    rings += r.rings;
    joined += r.joined;
    allowed += r.joined_allowed;
    whole += r.closed && r.one_piece && r.genus;
  }
  report << "## Holes with islands\n\n"
         << "Ring-shaped holes cut around islands into closed meshes "
            "(`CutIslandHoles`: a hole of t triangles whose first i stay, "
            "floating), filled by `FillHoles` with its defaults (islands "
            "joined automatically, stage fair, threads = all). Every "
            "output judged against the closed mesh: closed, one piece, the "
            "closed mesh's Euler characteristic (its genus), intersecting "
            "pairs with a new face (exact), mean distance to the removed "
            "surface in mean edge lengths. With `islands off` each loop is "
            "filled alone (CGAL's hole filling can only do that).\n\n"
         << rings << " holes with an island in " << rows.size()
         << " meshes: " << joined << " filled by one patch joining the island; "
         << whole << " of " << rows.size()
         << " outputs closed, in one piece, with the ground truth's genus; "
         << invalid << " defective. With allow_input_intersections (where "
         << "rings stay open), " << allowed
         << " rings are filled by one joined patch.\n\n"
         << "| mesh / cut | rings | joined and filled | closed | one piece "
            "| genus kept | pairs | distance | ms | islands off: filled "
            "loops, pieces | joined with allow_input_intersections "
            "|\n|---|---:|---:|---|---|---|---:|---:|---:|---|---:|\n";
  for (const Row& r : rows) {
    report << "| " << r.name << " | " << r.rings << " | " << r.joined << " | "
           << fill::Yes(r.closed) << " | " << fill::Yes(r.one_piece) << " | "
           << fill::Yes(r.genus) << " | " << r.v.pairs << " | "
           << Fixed(r.v.d_mean, 3) << " | " << Fixed(r.s.ms, 1) << " | "
           << r.filled_off << " of " << 2 * r.rings << ", " << r.pieces_off
           << " | " << r.joined_allowed << " |\n";
  }
  report << "\n";
  return invalid;
}

}  // namespace dot::bench
