// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl surface NETWORK -o SURFACE: a curve network (OBJ polylines or text
// blocks) turned into one surface, over the server or with --local; a
// table per patch, or the JSON report.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <regex>
#include <sstream>

#include "cli/inputs.h"
#include "cli/output.h"
#include "commands.h"
#include "exit_codes.h"
#include "remote_call.h"
#include "request_flags.h"
#include "surface_call.h"
#include "wire/surface_wire.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

// A patch's loops left open: some patch failed (exit 4).
constexpr const char* kOutcomePatchesOpen = "patches_open";

struct SurfaceFlags {
  std::string input, output, input_format, output_format;
  std::string stage = "fair";
  MetricWeights weights;
  bool absolute_weights = false;
  double density = 0;
  int fairing_continuity = 1;
  std::string cycles_file, islands = "inset";
  bool skip_longest = false, walls = false, ascii = false, json = false,
       local = false;
  double weld = 0;
  uint32_t time_budget_ms = 0;
  std::vector<std::vector<std::vector<int32_t>>> cycles;  // 0-based

  v1::SurfaceOptions ToWire() const {
    v1::SurfaceOptions o;
    if (HasNonZeroWeight(weights)) *o.mutable_weights() = wire::ToWire(weights);
    o.set_absolute_weights(absolute_weights);
    o.set_stage(stage == "triangulate" ? v1::FILL_STAGE_TRIANGULATE
                : stage == "refine"    ? v1::FILL_STAGE_REFINE
                                       : v1::FILL_STAGE_FAIR);
    o.set_density(density);
    o.set_fairing_continuity(fairing_continuity);
    o.set_skip_longest(skip_longest);
    o.set_walls(walls);
    o.set_weld_distance(weld);
    o.set_islands(islands == "hole"  ? v1::NETWORK_ISLANDS_HOLE
                  : islands == "off" ? v1::NETWORK_ISLANDS_OFF
                                     : v1::NETWORK_ISLANDS_INSET);
    o.set_time_budget_ms(time_budget_ms);
    for (const auto& patch : cycles) {
      v1::VertexCycle* c = o.add_cycles();
      for (const auto& loop : patch) {
        c->add_loops()->mutable_vertices()->Add(loop.begin(), loop.end());
      }
    }
    return o;
  }
};

// The cycles file: one patch a line, vertex ids numbered from 1 as OBJ
// numbers them, loops of one patch separated by '|'; '#' comments.
Status ReadCycles(const std::string& path,
                  std::vector<std::vector<std::vector<int32_t>>>* cycles) {
  std::ifstream in(path);
  if (!in) return InvalidArgument("cannot open cycles file '" + path + "'");
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::vector<std::vector<int32_t>> patch(1);
    std::istringstream s(line);
    for (std::string tok; s >> tok;) {
      if (tok == "|") {
        patch.emplace_back();
        continue;
      }
      char* end = nullptr;
      const long v = std::strtol(tok.c_str(), &end, 10);
      if (*end != '\0' || v < 1 || v > INT32_MAX) {
        return InvalidArgument(path + ": line " + std::to_string(lineno) +
                               ": '" + tok +
                               "' is not a vertex id (from 1) or '|'");
      }
      patch.back().push_back(static_cast<int32_t>(v - 1));
    }
    if (patch.size() == 1 && patch[0].empty()) continue;
    for (const auto& loop : patch) {
      if (loop.size() < 2) {
        return InvalidArgument(path + ": line " + std::to_string(lineno) +
                               ": a loop needs at least 2 listed vertices");
      }
    }
    cycles->push_back(std::move(patch));
  }
  if (cycles->empty()) return InvalidArgument(path + ": no cycles");
  return OkStatus();
}

Status ReadNetwork(const SurfaceFlags& f, CurveNetwork* network) {
  if (!IsStreamInput(f.input)) return ReadNetworkFile(f.input, network);
  std::ifstream file;
  std::istream* in = &std::cin;
  if (f.input != "-") {
    file.open(f.input);
    in = &file;
  }
  Status s = f.input_format == "txt" ? ReadNetworkText(*in, network)
                                     : ReadNetworkObj(*in, network);
  if (!s.ok()) s.message = "stdin: " + s.message;
  return s;
}

std::string Curves(const v1::PatchReport& p) {
  std::string out;
  for (const v1::PatchLoop& loop : p.loops()) {
    if (!out.empty()) out += " |";
    for (const v1::CurveUse& u : loop.curves()) {
      out += (out.empty() || out.back() == '|' ? "" : " ") +
             std::string(u.reversed() ? "~" : "") + std::to_string(u.curve());
    }
  }
  return out;
}

void PrintTable(const v1::SurfaceReport& r) {
  std::cout << " patch  verts  status    solver      refined faired     ms"
               "  curves (~: run backward); note\n";
  for (const v1::PatchReport& p : r.patches()) {
    std::string note = Curves(p);
    if (!p.reason().empty()) note += "; " + p.reason();
    std::cout << std::setw(6) << p.id() << std::setw(7) << p.boundary_vertices()
              << "  " << std::left << std::setw(10)
              << PatchStatusName(wire::PatchStatusFromWire(p.status()))
              << std::setw(12)
              << (p.fan()              ? "fan"
                  : p.solver().empty() ? "-"
                                       : p.solver())
              << std::right << std::setw(7) << p.refined_vertices()
              << std::setw(7) << (p.faired() ? "yes" : "no") << std::setw(7)
              << std::fixed << std::setprecision(1)
              << p.triangulate_ms() + p.refine_ms() << "  " << note << "\n";
    std::cout.unsetf(std::ios::fixed);
  }
}

void SurfaceOne(const SurfaceFlags& f, Context* ctx) {
  SurfaceOutcome o;
  std::string written;
  auto report = [&](const char* outcome, int exit_code,
                    const std::string& error, bool called) {
    RaiseExitCode(ctx, exit_code);
    if (f.json) {
      std::ostream& text = written == "-" ? std::cerr : std::cout;
      text << SurfaceOutcomeJson(f.input, o, written, outcome, exit_code, error,
                                 called)
           << std::endl;
    } else if (!error.empty()) {
      PrintError(f.input + ": " + error);
    }
  };
  const OutputTarget target = ResolveOutput(
      f.input, f.output, f.output_format,
      /*into_directory=*/false, {"surface", "ply", "off", "--output-format"});
  AtomicOutput sink;
  std::string output_error = target.error;
  if (output_error.empty()) output_error = sink.Open(target.Name());
  if (!output_error.empty()) {
    report(kOutcomeOutputError, kExitUsage, output_error, false);
    return;
  }
  CurveNetwork network;
  Status read = ReadNetwork(f, &network);
  SurfaceFlags flags = f;
  if (read.ok() && !f.cycles_file.empty()) {
    read = ReadCycles(f.cycles_file, &flags.cycles);
  }
  if (!read.ok()) {
    report(kOutcomeInputError, kExitUsage, read.message, false);
    return;
  }
  const bool bar = isatty(STDERR_FILENO) && !ctx->quiet;
  const auto on_progress = [bar](const v1::SurfaceProgress& p) {
    if (bar) {
      std::cerr << "\r  patches " << p.patches_done() << "/"
                << p.patches_total() << "\033[K" << std::flush;
    }
  };
  if (f.local) {
    o = SurfaceLocal(flags.ToWire(), network, on_progress);
  } else {
    const Connection server = ConnectOrReport(ctx, f.json);
    if (!server) return;
    o = server.calls->surface(server.channel, f.input, flags.ToWire(), network,
                              ctx->connection.timeout_s, on_progress);
  }
  if (bar) std::cerr << "\r\033[K" << std::flush;
  if (!o.status.ok()) {
    const int code = o.status.error_code() == grpc::StatusCode::INVALID_ARGUMENT
                         ? kExitUsage
                         : ExitCodeFor(o.status);
    // The service numbers as its arrays do; the files count from 1.
    static const std::regex kNumbered(
        "\\b(vertex|vertices|polylines?|cycles?) [0-9]");
    std::string numbering;
    if (code == kExitUsage &&
        std::regex_search(o.status.error_message(), kNumbered)) {
      numbering =
          " (numbered from 0: vertex 0 is the file's first point, "
          "polyline 0 its first";
      numbering += f.cycles_file.empty()
                       ? ")"
                       : ", cycle 0 the cycles file's first listed cycle)";
    }
    report(kOutcomeCallFailed, code,
           std::string(wire::GrpcCodeName(o.status.error_code())) + ": " +
               o.status.error_message() + numbering,
           true);
    return;
  }
  const Status w = WriteMesh(sink.stream(), target.format, o.mesh, f.ascii);
  const std::string write_error = w.ok() ? sink.Commit() : w.message;
  if (!write_error.empty()) {
    report(kOutcomeWriteFailed, kExitFailed, write_error, true);
    return;
  }
  written = target.Name();
  const v1::SurfaceReport& r = o.report;
  const int code = r.failed() > 0 ? kExitNoTriangulation : kExitOk;
  if (f.json) {
    report(r.failed() > 0 ? kOutcomePatchesOpen : kOutcomeOk, code, "", true);
    return;
  }
  RaiseExitCode(ctx, code);
  if (ctx->quiet) return;
  std::ostream& text = written == "-" ? std::cerr : std::cout;
  if (written != "-") PrintTable(r);
  text << f.input << ": " << r.surfaced() << " of " << r.patches_size()
       << " patches surfaced (" << r.curves_size() << " curves, "
       << r.junctions() << " junctions), " << (r.closed() ? "closed" : "open")
       << "; " << r.mesh_vertices() << " vertices, " << r.mesh_faces()
       << " faces, " << static_cast<int64_t>(o.latency_ms + 0.5) << " ms -> "
       << written << std::endl;
  for (const std::string& note : SurfaceNotes(r)) {
    text << "  note: " << note << "\n";
  }
}

}  // namespace

void AddSurfaceCommand(CLI::App& app, Context* ctx) {
  auto f = std::make_shared<SurfaceFlags>();
  CLI::App* cmd = app.add_subcommand(
      "surface",
      "Turn a curve network into one surface: its cycles found, each patch\n"
      "triangulated by DOT, refined, and the whole network faired.\n"
      "Example: dotctl surface sketch.obj -o surface.ply");
  cmd->add_option("network", f->input,
                  "curve network: .obj ('v' and 'l' lines), or text (blocks "
                  "of 'x y z' lines, a blank line between polylines); - for "
                  "stdin (with --input-format)")
      ->required();
  cmd->add_option("-o,--output", f->output,
                  "surface (.off, .obj, .ply, .stl; - for stdout as "
                  "--output-format); default: NAME.surface.ply beside the "
                  "input");
  cmd->add_option("--input-format", f->input_format,
                  "format of a network read from stdin (default obj)")
      ->check(CLI::IsMember({"obj", "txt"}));
  cmd->add_option("--output-format", f->output_format,
                  "format of the surface on stdout, or of an -o file without "
                  "an extension (default: off on stdout)")
      ->check(CLI::IsMember({"off", "obj", "ply", "stl"}));
  cmd->add_option("--stage", f->stage,
                  "triangulate (the DOT patches), refine (+ Liepa "
                  "refinement) or fair (+ fairing over the whole network)")
      ->check(CLI::IsMember({"triangulate", "refine", "fair"}))
      ->capture_default_str();
  cmd->add_option("--cycles", f->cycles_file,
                  "the patches, given: one per line, vertex ids from 1 (as "
                  "OBJ numbers them; listing the junctions is enough where "
                  "one curve joins them), loops of a patch separated by "
                  "'|'; default: found automatically")
      ->group("Patches");
  cmd->add_flag("--skip-longest", f->skip_longest,
                "leave the longest found cycle open (an open sheet's rim)")
      ->group("Patches");
  cmd->add_option("--islands", f->islands,
                  "a lone closed curve inside a found face: inset (an island "
                  "of the face and a patch of its own), hole (an island "
                  "only) or off (a patch of its own only)")
      ->check(CLI::IsMember({"inset", "hole", "off"}))
      ->capture_default_str()
      ->group("Patches");
  cmd->add_flag("--walls", f->walls,
                "also find walls: flat cycles that make a third patch on "
                "their curves (a partition inside a box; without it a ring "
                "of curves around a body is only a line between two "
                "patches)")
      ->group("Patches");
  cmd->add_option(
         "--weld", f->weld,
         "weld each stroke end to the nearest point within this distance "
         "(the network's units) not on its own stroke: strokes "
         "whose ends nearly meet become junctions (default 0: only "
         "points at the same place)")
      ->check(CLI::NonNegativeNumber)
      ->group("Patches");
  const std::string weights =
      "Metric weights (default: --squared-dihedral 1 --normal-deviation 0.25 "
      "--area "
      "0.01)";
  AddWeightFlags(cmd, &f->weights, weights,
                 {"area, per squared mean cycle edge length",
                  "perimeter, per mean cycle edge length",
                  "deviation from the normals the patches on a curve share",
                  "triangle shape (0 equilateral, 1 flat)", "bending angle",
                  "squared bending angle (fair patches)"});
  cmd->add_flag("--absolute-weights", f->absolute_weights,
                "area and perimeter weights in the network's units")
      ->group(weights);
  cmd->add_option("--density", f->density,
                  "refinement density factor (default sqrt(2))")
      ->group("Refine and fair");
  cmd->add_option("--fairing-continuity", f->fairing_continuity,
                  "0 membrane, 1 thin plate, 2 minimum variation")
      ->check(CLI::Range(0, 2))
      ->capture_default_str()
      ->group("Refine and fair");
  cmd->add_flag("--ascii", f->ascii,
                "write PLY and STL as ASCII (default binary)");
  cmd->add_option("--time-budget-ms", f->time_budget_ms,
                  "compute time allowed (0: the server's limit)");
  cmd->add_flag("--json", f->json, "the report as one JSON object on stdout");
  cmd->add_flag("--local", f->local, "compute in this process, no server");
  cmd->callback([f, ctx] {
    if (f->input == "-" && f->output.empty()) f->output = "-";
    SurfaceOne(*f, ctx);
  });
}

}  // namespace dot::client
