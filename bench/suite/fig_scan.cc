// SPDX-License-Identifier: AGPL-3.0-or-later
// Hole filling at scan size, as a user pays for it: whole processes reading
// the same OFF file and writing a PLY. libcgal-demo's bunny00 (75 k faces)
// subdivided twice by midpoints (1.2 M faces) with 10, 100 and 1,000 holes
// of 200 triangles cut by CutHoles (what `dotctl generate holes` runs), and
// three times (4.8 M faces) with 30 holes of 3,000:
//  - dot: `dotctl fill-holes --local --json` (its report says how many
//    holes it filled), and once more with -v for the time of each phase;
//  - CGAL 5.5: cgal_fill_file (every border cycle through
//    triangulate_refine_and_fair_hole), in the same run;
//  - the 4.8 M mesh once through a dot-server with default limits.
// Medians of up to `reps` runs (3 at most: a run takes seconds), peak RSS
// (wait4), the time with k holes over the time with 10, and dot over CGAL.
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>
#include <unordered_map>

#include "dot/dot.h"
#include "dot/hole_generator.h"
#include "measure.h"
#include "process.h"
#include "suite.h"

namespace dot::bench {
namespace {

using Clock = std::chrono::steady_clock;

// Each triangle into four at its edges' midpoints: the same surface, four
// times the faces, as a finer scan of it.
MeshData Subdivide(const MeshData& in) {
  MeshData out{in.vertices, {}};
  std::unordered_map<uint64_t, int32_t> midpoint;
  midpoint.reserve(in.triangles.size() * 2);
  auto mid = [&](int32_t a, int32_t b) {
    const uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) |
                         static_cast<uint32_t>(std::max(a, b));
    auto [it, added] =
        midpoint.emplace(key, static_cast<int32_t>(out.vertices.size()));
    if (added) {
      const Vec3 &p = in.vertices[a], &q = in.vertices[b];
      out.vertices.push_back(
          {(p.x + q.x) / 2, (p.y + q.y) / 2, (p.z + q.z) / 2});
    }
    return it->second;
  };
  out.triangles.reserve(4 * in.triangles.size());
  for (const Triangle& t : in.triangles) {
    const int32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]),
                  ca = mid(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

struct Tool {
  double seconds = NAN, peak = NAN;
  std::vector<double> runs;
  int failed = 0;  // runs that did not exit 0
};

Tool Repeat(int reps, const std::vector<std::string>& argv,
            const std::string& log) {
  Tool t;
  std::vector<double> peaks;
  for (int r = 0; r < reps; ++r) {
    const ProcessRun run = RunProcess(argv, log);
    if (run.exit_code != 0) ++t.failed;
    t.runs.push_back(run.seconds);
    peaks.push_back(run.peak_bytes);
  }
  t.seconds = Median(t.runs);
  t.peak = Median(peaks);
  return t;
}

std::string Runs(const std::vector<double>& runs) {
  std::string out;
  for (double s : runs) out += (out.empty() ? "" : ", ") + Fixed(s, 2);
  return out;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The "phases: ..." line dotctl -v prints.
std::string Phases(const std::string& log) {
  const size_t at = log.rfind("phases: ");
  return at == std::string::npos
             ? "-"
             : log.substr(at + 8, log.find('\n', at) - (at + 8));
}

}  // namespace

int RunScan(const Config& config, std::ostream& report) {
  report << "## Hole filling at scan size\n\n";
  MeshData bunny;
  const std::string source = config.mesh_dir + "/bunny00.off";
  if (!ReadMeshFile(source, &bunny).ok()) {
    report << "`" << source << "` missing (install libcgal-demo).\n\n";
    return 0;
  }
  const std::filesystem::path dir =
      std::filesystem::path(config.out_dir) / "scan-data";
  std::filesystem::create_directories(dir);
  const std::string dotctl = config.dotctl_path, cgal = config.cgal_fill_path;
  const int reps = config.quick ? 1 : std::min(config.reps, 3);
  struct Case {
    int levels, holes, triangles;
  };
  const std::vector<Case> cases =
      config.quick
          ? std::vector<Case>{{1, 10, 200}, {1, 100, 200}}
          : std::vector<Case>{
                {2, 10, 200}, {2, 100, 200}, {2, 1000, 200}, {3, 30, 3000}};
  std::ofstream csv(config.Path("scan.csv"));
  csv << "faces,holes,generate_ms,dot_s,dot_peak_mib,dot_filled,cgal_s,"
         "cgal_peak_mib,dot_over_cgal\n";
  report << "libcgal-demo's bunny00 subdivided by midpoints, holes of the "
            "given size cut at seeds apart from each other; each tool a whole "
            "process reading the OFF and writing a PLY (`dotctl fill-holes "
            "--local`; CGAL 5.5's `triangulate_refine_and_fair_hole` on every "
            "border cycle, `cgal_fill_file`), median of "
         << reps
         << " runs, peak RSS. Data: `scan.csv`.\n\n"
            "| faces | holes | generate | dot (runs) | dot peak | filled | "
            "CGAL (runs) | CGAL peak | dot/CGAL | vs 10 holes |\n"
            "|---|---|---|---|---|---|---|---|---|---|\n";
  int invalid = 0;
  int levels = 0;
  MeshData mesh = bunny;
  double ten_holes = NAN;
  std::vector<std::string> phase_lines;
  std::string largest;
  for (const Case& c : cases) {
    while (levels < c.levels) {
      mesh = Subdivide(mesh);
      ++levels;
    }
    const auto t0 = Clock::now();
    MeshData holey, removed;
    if (!CutHoles(mesh, c.holes, c.triangles, 7, &holey, &removed).ok()) {
      report << "| " << mesh.triangles.size() << " | " << c.holes
             << " | no room | | | | | | | |\n";
      continue;
    }
    const double generate_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    const std::string input = (dir / ("bunny" + std::to_string(levels) + "-" +
                                      std::to_string(c.holes) + ".off"))
                                  .string();
    const std::string log = (dir / "run.log").string();
    if (!WriteMeshFile(input, holey).ok()) {
      report << "Could not write `" << input << "`.\n\n";
      return invalid + 1;
    }
    removed = {};
    const std::string output = (dir / "out.ply").string();
    const Tool ours = Repeat(
        reps, {dotctl, "fill-holes", "--local", "--json", input, "-o", output},
        log);
    const int filled = static_cast<int>(JsonNumber(ReadAll(log), "filled"));
    if (ours.failed > 0 || filled != c.holes) ++invalid;
    // The phases of one more run, for the split of the time.
    RunProcess({dotctl, "-v", "fill-holes", "--local", input, "-o", output},
               log);
    phase_lines.push_back(std::to_string(holey.triangles.size()) + " faces, " +
                          std::to_string(c.holes) +
                          " holes: " + Phases(ReadAll(log)));
    const Tool theirs =
        cgal.empty()
            ? Tool{}
            : Repeat(reps, {cgal, input, (dir / "cgal.ply").string()}, log);
    if (c.holes == 10) ten_holes = ours.seconds;
    const double versus = ours.seconds / theirs.seconds;
    report << "| " << holey.triangles.size() << " | " << c.holes << " | "
           << Fixed(generate_ms, 0) << " ms | " << Fixed(ours.seconds, 2)
           << " s (" << Runs(ours.runs) << ") | " << Mib(ours.peak) << " | "
           << filled << (ours.failed ? " (failed)" : "") << " | "
           << Fixed(theirs.seconds, 2) << " s (" << Runs(theirs.runs) << ") | "
           << Mib(theirs.peak) << " | " << Fixed(versus, 2) << " | "
           << (levels == 2 || config.quick ? Fixed(ours.seconds / ten_holes, 2)
                                           : "-")
           << " |\n";
    csv << holey.triangles.size() << ',' << c.holes << ',' << generate_ms << ','
        << ours.seconds << ',' << ours.peak / (1 << 20) << ',' << filled << ','
        << theirs.seconds << ',' << theirs.peak / (1 << 20) << ',' << versus
        << '\n';
    largest = input;
  }
  report << "\nWhere dot's time goes (`dotctl -v`, one run each):\n\n";
  for (const std::string& line : phase_lines) report << "- " << line << "\n";
  // The largest mesh through a server with its default limits.
  if (!largest.empty() && !config.server_path.empty()) {
    const int port = FreeLoopbackPort();
    const std::string address = "127.0.0.1:" + std::to_string(port);
    const int server = StartProcess({config.server_path, "--listen=" + address,
                                     "--metrics-port=0", "--log-level=warn"},
                                    (dir / "server.log").string());
    bool up = false;
    for (int i = 0; i < 100 && !up && server > 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      up = RunProcess({dotctl, "-s", address, "health"},
                      (dir / "health.log").string())
               .exit_code == 0;
    }
    const std::string log = (dir / "remote.log").string();
    const ProcessRun remote =
        RunProcess({dotctl, "-s", address, "fill-holes", "--json", largest,
                    "-o", (dir / "remote.ply").string()},
                   log);
    const int filled = static_cast<int>(JsonNumber(ReadAll(log), "filled"));
    if (remote.exit_code != 0) ++invalid;
    ProcessRun served;
    if (server > 0) {
      ::kill(server, SIGTERM);
      served = WaitProcess(server, Clock::now());
    }
    report << "\nThe last mesh through `dot-server` (default limits) on "
              "127.0.0.1: "
           << (remote.exit_code == 0
                   ? "succeeded"
                   : "FAILED (exit " + std::to_string(remote.exit_code) + ")")
           << ", " << filled << " holes filled, " << Fixed(remote.seconds, 2)
           << " s, client peak " << Mib(remote.peak_bytes) << ", server peak "
           << Mib(served.peak_bytes) << ".\n";
  }
  report << "\n";
  std::filesystem::remove_all(dir);
  return invalid;
}

}  // namespace dot::bench
