// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl fill-holes MESH -o OUT: every hole of a mesh filled (DOT, then
// refinement and fairing), over the server or with --local; a table per
// hole, or the JSON report.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "cli/inputs.h"
#include "commands.h"
#include "exit_codes.h"
#include "fill_call.h"
#include "remote_call.h"
#include "request_flags.h"
#include "view_page.h"
#include "wire/fill_wire.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

struct FillFlags {
  std::vector<std::string> inputs;  // as given: files, directories, -
  std::string input, output, stdin_format, output_format;  // input: one
  std::string stage = "fair";
  std::string report_page;  // --report: a file, or a directory (several)
  uint32_t max_hole_edges = 0;
  double max_hole_diameter = 0;
  bool skip_longest = false;
  std::vector<int32_t> holes;
  std::vector<uint32_t> loops_through;
  std::string islands = "auto";
  std::vector<std::vector<int32_t>> join;
  MetricWeights weights;
  bool absolute_weights = false;
  double density = 0;
  int fairing_continuity = 1;
  bool no_repair = false, ascii = false, dry_run = false, triangles = false;
  bool allow_input_intersections = false;
  bool json = false, local = false;
  uint32_t time_budget_ms = 0;

  v1::FillOptions ToWire() const {
    v1::FillOptions o;
    if (HasNonZeroWeight(weights)) {
      *o.mutable_weights() = wire::ToWire(weights);
    }
    o.set_absolute_weights(absolute_weights);
    o.set_stage(stage == "triangulate" ? v1::FILL_STAGE_TRIANGULATE
                : stage == "refine"    ? v1::FILL_STAGE_REFINE
                                       : v1::FILL_STAGE_FAIR);
    o.set_max_hole_edges(max_hole_edges);
    o.set_max_hole_diameter(max_hole_diameter);
    o.set_skip_longest(skip_longest);
    for (int32_t h : holes) o.add_holes(h);
    for (uint32_t v : loops_through) o.add_loops_through(v);
    o.set_islands(islands == "off" ? v1::ISLANDS_OFF : v1::ISLANDS_AUTO);
    for (const std::vector<int32_t>& group : join) {
      o.add_join()->mutable_loops()->Add(group.begin(), group.end());
    }
    o.set_density(density);
    o.set_fairing_continuity(fairing_continuity);
    o.set_no_repair(no_repair);
    o.set_time_budget_ms(time_budget_ms);
    o.set_dry_run(dry_run);
    o.set_allow_input_intersections(allow_input_intersections);
    o.set_keep_polygons(!triangles);
    return o;
  }
};

void AddFlags(CLI::App* cmd, FillFlags* f) {
  cmd->add_option("mesh", f->inputs,
                  "mesh files (.off, .obj, .ply, .stl) or directories of "
                  "them, or - for stdin (with --input-format); several "
                  "need -o DIR/ or none (each beside its input)")
      ->required();
  cmd->add_option("-o,--output", f->output,
                  "filled mesh (.off, .obj, .ply, .stl; - for stdout as "
                  "--output-format); default: NAME.filled.ply beside the "
                  "input");
  cmd->add_option("--input-format", f->stdin_format,
                  "format of a mesh read from stdin (- or /dev/stdin)")
      ->check(CLI::IsMember({"off", "obj", "ply", "stl"}));
  cmd->add_option("--output-format", f->output_format,
                  "format of the filled mesh on stdout, or of an -o file "
                  "without an extension (default: off on stdout)")
      ->check(CLI::IsMember({"off", "obj", "ply", "stl"}));
  cmd->add_option("--stage", f->stage,
                  "triangulate (the DOT patch), refine (+ Liepa refinement) "
                  "or fair (+ fairing: the finished surface)")
      ->check(CLI::IsMember({"triangulate", "refine", "fair"}))
      ->capture_default_str();
  cmd->add_option("--max-hole-edges", f->max_hole_edges,
                  "fill only holes with at most this many edges (0: any)")
      ->group("Which holes");
  cmd->add_option("--max-hole-diameter", f->max_hole_diameter,
                  "fill only holes at most this wide (bounding-box diagonal; "
                  "0: any)")
      ->check(CLI::Validator(
          [](std::string& value) {
            // CLI::NonNegativeNumber printed the range up to DBL_MAX in full.
            char* end = nullptr;
            const double d = std::strtod(value.c_str(), &end);
            return end != value.c_str() && *end == '\0' && d >= 0
                       ? std::string()
                       : "must be a number >= 0, got " + value;
          },
          "FLOAT >= 0"))
      ->group("Which holes");
  cmd->add_flag("--skip-longest", f->skip_longest,
                "leave the longest border open (a terrain's rim)")
      ->group("Which holes");
  cmd->add_option("--holes", f->holes, "only these hole ids, e.g. 3,7")
      ->delimiter(',')
      ->group("Which holes");
  cmd->add_option("--loops-through", f->loops_through,
                  "only the holes through these vertices (ids of the input "
                  "file, from 0), e.g. 120,4077")
      ->delimiter(',')
      ->group("Which holes");
  cmd->add_option("--islands", f->islands,
                  "auto: a hole's islands (pieces of surface floating "
                  "inside it) are joined to its rim in one patch; off: "
                  "every loop is filled alone")
      ->check(CLI::IsMember({"auto", "off"}))
      ->capture_default_str()
      ->group("Which holes");
  cmd->add_option_function<std::vector<std::string>>(
         "--join",
         [f](const std::vector<std::string>& groups) {
           for (const std::string& g : groups) {
             std::vector<int32_t> ids;
             std::istringstream in(g);
             for (std::string id; std::getline(in, id, ',');) {
               ids.push_back(static_cast<int32_t>(std::stol(id)));
             }
             f->join.push_back(std::move(ids));
           }
         },
         "fill these holes by one patch, e.g. --join 3,7 (a rim and its "
         "islands, or two borders to bridge); repeatable")
      ->check(CLI::Validator(
          [](std::string& value) {
            std::istringstream in(value);
            int count = 0;
            for (std::string id; std::getline(in, id, ',');) {
              char* end = nullptr;
              const long v = std::strtol(id.c_str(), &end, 10);
              if (id.empty() || *end != '\0' || v < 0 || v > INT32_MAX) {
                return "must be hole ids separated by commas, got " + value;
              }
              ++count;
            }
            return count >= 2 ? std::string()
                              : "needs at least 2 hole ids, got " + value;
          },
          "ID,ID[,ID...]"))
      ->group("Which holes");
  AddWeightFlags(cmd, &f->weights,
                 "Metric weights (default: --squared-dihedral 1 --area 0.01)",
                 {"area, per squared mean boundary edge length",
                  "perimeter, per mean boundary edge length",
                  "deviation from the surface normals",
                  "triangle shape (0 equilateral, 1 flat)",
                  "bending angle, the surrounding faces included",
                  "squared bending angle (fair patches)"});
  cmd->add_flag("--absolute-weights", f->absolute_weights,
                "area and perimeter weights in the mesh's units, not per "
                "hole scale")
      ->group("Metric weights (default: --squared-dihedral 1 --area 0.01)");
  cmd->add_option("--density", f->density,
                  "refinement density factor (default sqrt(2))")
      ->group("Refine and fair");
  cmd->add_option("--fairing-continuity", f->fairing_continuity,
                  "0 membrane, 1 thin plate, 2 minimum variation")
      ->check(CLI::Range(0, 2))
      ->capture_default_str()
      ->group("Refine and fair");
  cmd->add_flag("--no-repair", f->no_repair,
                "use the mesh as it is (no vertex merging, orientation, ...)");
  cmd->add_flag("--allow-input-intersections", f->allow_input_intersections,
                "fill a hole whose every patch meets the mesh when the mesh "
                "already intersects itself near it (the report counts both); "
                "by default such holes stay open");
  cmd->add_flag("--dry-run", f->dry_run,
                "list the holes (size, place, selected or why not) and fill "
                "none; nothing is written");
  cmd->add_flag("--triangles", f->triangles,
                "write the repaired triangles (polygons triangulated; "
                "normals, colours and UVs kept); by default the mesh keeps "
                "its polygons where no patch split one");
  cmd->add_flag("--ascii", f->ascii,
                "write PLY and STL as ASCII (default binary)");
  cmd->add_option("--time-budget-ms", f->time_budget_ms,
                  "compute time allowed (0: the server's limit)");
  cmd->add_flag("--json", f->json, "the report as one JSON object on stdout");
  cmd->add_option("--report", f->report_page,
                  "also write a page to look at the result in a browser "
                  "(REPORT.html; with several meshes a directory, NAME.html "
                  "in it): the mesh before and after, patches highlighted, "
                  "the holes listed");
  cmd->add_flag("--local", f->local, "fill in this process, no server");
}

// Where --report's page for `input` goes: the file named, or NAME.html in
// the directory named (several meshes).
std::string ReportPagePath(const FillFlags& f) {
  std::error_code ec;
  const std::filesystem::path named(f.report_page);
  if (f.report_page.back() != '/' &&
      !std::filesystem::is_directory(named, ec)) {
    return f.report_page;
  }
  std::string stem = std::filesystem::path(f.input).stem().string();
  if (IsStreamInput(f.input)) stem = "stdin";
  std::filesystem::create_directories(named, ec);  // a/new/dir/: made
  return (named / (stem + ".html")).string();
}

// The viewer page of a fill, into `out`: "" or why it could not be written.
std::string WriteReportPage(const FillFlags& f, const PolygonSoup& before,
                            const FillOutcome& o, AtomicOutput* out) {
  const PolygonSoup after = o.as_sent ? PolygonSoup() : ToSoup(o.mesh);
  const v1::FillReport& r = o.report;
  ViewPage page;
  page.title = f.input == "-" ? "stdin" : f.input;
  page.summary =
      std::to_string(r.filled()) + " of " +
      std::to_string(r.loops() - r.skipped()) + " holes filled" +
      (r.skipped() ? " (" + std::to_string(r.skipped()) + " skipped)" : "") +
      (r.closed() ? ", closed" : ", still open") + "; +" +
      std::to_string(r.added_vertices()) + " vertices, +" +
      std::to_string(r.added_faces()) + " faces (stage " + f.stage + ")";
  page.before = &before;
  page.after = o.as_sent ? &o.soup : &after;
  page.report = &r;
  std::string html;
  const Status s = RenderViewPage(page, &html);
  if (!s.ok()) return s.message;
  out->stream() << html;
  return out->Commit();
}

// The note column: "pinched loop", "joins islands 3, 5" on a rim whose
// patch joins other loops, and the reason, separated by "; ".
std::string HoleNote(const v1::HoleReport& h) {
  std::string note = h.pinched() ? "pinched loop" : "";
  if (!h.joined().empty()) {
    note += std::string(note.empty() ? "" : "; ") +
            (h.joined_size() == 1 ? "joins island " : "joins islands ");
    for (int k = 0; k < h.joined_size(); ++k) {
      note += (k ? ", " : "") + std::to_string(h.joined(k));
    }
  }
  if (!h.reason().empty()) {
    note += (note.empty() ? "" : "; ") + h.reason();
  }
  return note;
}

void PrintTable(const v1::FillReport& r) {
  std::cout << " hole edges  status            escalation       inserted "
               "refined faired     ms  note\n";
  for (const v1::HoleReport& h : r.holes()) {
    const double ms =
        h.triangulate_ms() + h.refine_ms() + h.fair_ms() + h.check_ms();
    std::cout << std::setw(5) << h.id() << std::setw(6) << h.boundary_vertices()
              << "  " << std::left << std::setw(18)
              << HoleStatusName(wire::HoleStatusFromWire(h.status()))
              << std::setw(17)
              << (h.escalation() == v1::ESCALATION_NONE
                      ? std::string_view("-")
                      : EscalationName(
                            wire::EscalationFromWire(h.escalation())))
              << std::right << std::setw(8) << h.boundary_inserted()
              << std::setw(8) << h.refined_vertices() << std::setw(7)
              << (h.faired() ? "yes" : "no") << std::setw(7) << std::fixed
              << std::setprecision(1) << ms << "  " << HoleNote(h) << "\n";
    std::cout.unsetf(std::ios::fixed);
  }
}

// --dry-run: each loop, its size and place, and whether it is selected.
void PrintListing(const std::string& input, const v1::FillReport& r) {
  std::cout << " hole edges      diameter     perimeter  centroid"
               "                                  status   note\n";
  for (const v1::HoleReport& h : r.holes()) {
    std::ostringstream centroid;
    centroid.precision(6);
    for (int k = 0; k < h.centroid_size(); ++k) {
      centroid << (k ? " " : "") << h.centroid(k);
    }
    std::cout << std::setw(5) << h.id() << std::setw(6) << h.boundary_vertices()
              << std::setprecision(6) << std::setw(14) << h.diameter()
              << std::setw(14) << h.perimeter() << "  " << std::left
              << std::setw(40) << centroid.str() << std::setw(9)
              << HoleStatusName(wire::HoleStatusFromWire(h.status()))
              << std::right << HoleNote(h) << "\n";
  }
  std::cout << input << ": " << r.loops() << " holes, " << r.listed()
            << " would be filled"
            << (r.skipped() ? " (" + std::to_string(r.skipped()) + " skipped)"
                            : "")
            << " (dry run: nothing filled or written)\n";
}

// Wall time per phase, in the order they came: "read 5.1 s, repair ...".
class PhaseClock {
 public:
  // Ends the phase under way, starts `name` ("" ends only); a name seen
  // again (holes, report after report) continues its phase.
  void Start(const std::string& name) {
    const auto now = std::chrono::steady_clock::now();
    if (!phases_.empty()) {
      phases_.back().second +=
          std::chrono::duration<double>(now - since_).count();
    }
    since_ = now;
    if (!name.empty() && (phases_.empty() || phases_.back().first != name)) {
      phases_.emplace_back(name, 0.0);
    }
  }
  std::string Summary() const {
    std::ostringstream out;
    out.precision(2);
    out << std::fixed;
    for (size_t i = 0; i < phases_.size(); ++i) {
      out << (i ? ", " : "") << phases_[i].first << " " << phases_[i].second
          << " s";
    }
    return out.str();
  }

 private:
  std::vector<std::pair<std::string, double>> phases_;
  std::chrono::steady_clock::time_point since_;
};

// "  holes 40/1000, 12 s left" for the terminal's status line.
std::string ProgressLine(const v1::FillProgress& p) {
  switch (p.phase()) {
    case v1::FILL_PHASE_REPAIR:
      return "  repairing the mesh";
    case v1::FILL_PHASE_LOOPS:
      return "  finding the holes";
    case v1::FILL_PHASE_MERGE:
      return "  merging " + std::to_string(p.holes_total()) + " patches";
    default:
      break;
  }
  std::string line = "  holes " + std::to_string(p.holes_done()) + "/" +
                     std::to_string(p.holes_total());
  if (p.eta_ms() > 0) {
    line += ", " + std::to_string(static_cast<int64_t>(p.eta_ms() / 1000 + 1)) +
            " s left";
  }
  return line;
}

// One mesh: read, fill (here or on the server, over `server`, connected
// on first use), write, report.
void FillOne(const FillFlags& f, Context* ctx, Connection* server) {
  FillOutcome o;
  std::string written;
  // Every outcome, as text on stderr or as one JSON object.
  auto report = [&](const char* outcome, int exit_code,
                    const std::string& error, bool called) {
    ctx->exit_code = std::max(ctx->exit_code, exit_code);
    if (f.json) {
      std::ostream& text = written == "-" ? std::cerr : std::cout;
      text << FillOutcomeJson(f.input, o, written, outcome, exit_code, error,
                              called)
           << std::endl;
    } else if (!error.empty()) {
      std::cerr << "dotctl: " << f.input << ": " << error << "\n";
    }
  };
  if (f.input == "/dev/stdin" && f.stdin_format.empty()) {
    report(kOutcomeInputError, kExitUsage,
           "reading a mesh from stdin needs --input-format", false);
    return;
  }
  // Checked before the work: where the mesh goes, and that it can.
  const OutputTarget target = ResolveOutput(
      f.input, f.output, f.output_format, /*into_directory=*/false,
      {"filled", "ply", "off", "--output-format"});
  AtomicOutput sink;
  std::string output_error = f.dry_run ? "" : target.error;
  if (f.dry_run && !f.output.empty()) {
    output_error = "--dry-run writes no mesh: leave out -o " + f.output;
  }
  if (f.dry_run && !f.report_page.empty()) {
    output_error = "--dry-run fills nothing to show: use dotctl view " +
                   f.input + " to see its holes";
  }
  if (output_error.empty() && !f.dry_run) {
    output_error = sink.Open(target.Name());
  }
  AtomicOutput page_sink;
  const std::string page_path = f.report_page.empty() ? "" : ReportPagePath(f);
  if (output_error.empty() && !page_path.empty()) {
    // One file, one output: the page never replaces the mesh read or
    // written, and stdout takes one of them.
    if (SameFile(f.input, page_path)) {
      output_error = "--report '" + page_path +
                     "' would overwrite the input: name another file";
    } else if (page_path == "-" ? target.to_stdout || f.json
                                : SameFile(target.Name(), page_path)) {
      output_error =
          page_path == "-"
              ? "--report - and " + std::string(f.json ? "--json" : "-o -") +
                    " would both write stdout"
              : "--report '" + page_path + "' would overwrite the filled mesh";
    }
  }
  if (output_error.empty() && !page_path.empty()) {
    output_error = page_sink.Open(page_path);
    if (!output_error.empty()) output_error = "--report: " + output_error;
  }
  if (!output_error.empty()) {
    report(kOutcomeOutputError, kExitUsage, output_error, false);
    return;
  }
  // On a terminal, the phase and the holes done, on one line of stderr.
  const bool bar = isatty(STDERR_FILENO) && !ctx->quiet;
  auto phase = [bar](const std::string& text) {
    if (bar) std::cerr << "\r" << text << "\033[K" << std::flush;
  };
  // -v: where the time went, phase by phase (the fill's phases as its
  // progress reports them).
  PhaseClock clock;
  const auto on_progress = [&phase, &clock](const v1::FillProgress& p) {
    phase(ProgressLine(p));
    clock.Start(std::string(FillPhaseName(wire::FillPhaseFromWire(p.phase()))));
  };
  phase("  reading " + f.input);
  clock.Start("read");
  PolygonSoup soup;
  std::vector<std::string> read_notes;
  const Status read =
      ReadMeshInput(f.input, f.stdin_format, &soup, &read_notes);
  phase("");
  if (!read.ok()) {
    report(kOutcomeInputError, kExitUsage, read.message, false);
    return;
  }
  // --report shows the mesh as read beside the result.
  PolygonSoup before;
  if (!f.report_page.empty() && !f.dry_run) before = soup;
  if (f.local) {
    o = FillLocal(f.input, f.ToWire(), std::move(soup), on_progress);
  } else {
    if (!*server) *server = ConnectOrReport(ctx, f.json);
    if (!*server) return;
    phase("  uploading " + std::to_string(soup.faces.size()) + " faces");
    clock.Start("upload");
    o = server->calls->fill(server->channel, f.input, f.ToWire(), soup,
                            ctx->connection.timeout_s, on_progress);
  }
  phase("");
  o.notes.insert(o.notes.begin(), read_notes.begin(), read_notes.end());
  if (!o.status.ok() && !o.partial) {
    // A mesh or options the service refuses are unusable input (2).
    const int code = o.status.error_code() == grpc::StatusCode::INVALID_ARGUMENT
                         ? kExitUsage
                         : ExitCodeFor(o.status);
    report(kOutcomeCallFailed, code,
           std::string(wire::GrpcCodeName(o.status.error_code())) + ": " +
               o.status.error_message(),
           true);
    return;
  }
  if (f.dry_run) {
    if (f.json) {
      report(kOutcomeOk, kExitOk, "", true);
    } else if (!ctx->quiet) {
      PrintListing(f.input, o.report);
    }
    return;
  }
  phase("  writing " + target.Name());
  clock.Start("write");
  Status w =
      o.as_sent
          ? WriteSoup(sink.stream(), target.format, o.soup, f.ascii, &o.notes)
          : WriteMesh(sink.stream(), target.format, o.mesh, f.ascii);
  phase("");
  clock.Start("");
  if (ctx->verbose) std::cerr << "phases: " << clock.Summary() << "\n";
  std::string write_error = w.ok() ? sink.Commit() : w.message;
  if (!write_error.empty()) {
    report(kOutcomeWriteFailed, kExitFailed, write_error, true);
    return;
  }
  written = target.Name();
  if (!page_path.empty()) {
    phase("  writing the report page");
    const std::string page_error = WriteReportPage(f, before, o, &page_sink);
    phase("");
    if (!page_error.empty()) {
      report(kOutcomeWriteFailed, kExitFailed, "--report: " + page_error, true);
      return;
    }
    o.page = page_path;
  }
  const v1::FillReport& r = o.report;
  const std::string stopped =
      o.partial ? std::string(wire::GrpcCodeName(o.status.error_code())) +
                      ": " + o.status.error_message()
                : "";
  const int code = o.partial          ? kExitPartial
                   : r.unfilled() > 0 ? kExitNoTriangulation
                                      : kExitOk;
  if (f.json) {
    report(o.partial          ? kOutcomePartial
           : r.unfilled() > 0 ? kOutcomeHolesOpen
                              : kOutcomeOk,
           code, stopped, true);
    return;
  }
  ctx->exit_code = std::max(ctx->exit_code, code);
  if (ctx->quiet) return;  // -q: errors only
  // With the mesh on stdout, the report goes to stderr.
  std::ostream& text = written == "-" ? std::cerr : std::cout;
  if (written != "-") PrintTable(r);
  text << f.input << ": " << r.filled() << " of " << r.loops() - r.skipped()
       << " holes filled"
       << (r.skipped() ? " (" + std::to_string(r.skipped()) + " skipped)" : "")
       << ", " << (r.closed() ? "closed" : "still open") << "; +"
       << r.added_vertices() << " vertices, +" << r.added_faces() << " faces, "
       << static_cast<int64_t>(o.latency_ms + 0.5) << " ms -> " << written
       << std::endl;
  if (!o.page.empty()) text << "  report page: " << o.page << "\n";
  if (o.partial) {
    text << "  stopped early: " << stopped << "\n";
  }
  for (const std::string& note : FillNotes(r)) text << "  " << note << "\n";
  for (const std::string& note : o.notes) text << "  note: " << note << "\n";
}

}  // namespace

void AddFillHolesCommand(CLI::App& app, Context* ctx) {
  auto flags = std::make_shared<FillFlags>();
  CLI::App* cmd = app.add_subcommand(
      "fill-holes",
      "Fill every hole of a mesh: DOT patches, refined and faired.\n"
      "Example: dotctl fill-holes scan.ply -o closed.ply --max-hole-edges 500");
  AddFlags(cmd, flags.get());
  cmd->callback([flags, ctx] {
    std::string error;
    const std::vector<std::string> inputs =
        ExpandInputs(flags->inputs, &error, {".off", ".obj", ".ply", ".stl"});
    const std::string& out = flags->output;
    std::string why;
    if (!error.empty()) {
      why = error;
    } else if (inputs.size() > 1 && out == "-") {
      why = "several meshes cannot all go to stdout: use -o DIR/";
    } else if (inputs.size() > 1 && !out.empty() && out.back() != '/' &&
               !std::filesystem::is_directory(out)) {
      why = "several meshes need a directory for -o (end it with '/')";
    } else if (inputs.size() > 1 && !flags->report_page.empty() &&
               flags->report_page.back() != '/' &&
               !std::filesystem::is_directory(flags->report_page)) {
      why = "several meshes need a directory for --report (end it with '/')";
    } else if (inputs.size() > 1 && flags->dry_run && !out.empty()) {
      why = "--dry-run writes no mesh: leave out -o " + out;
    }
    // Two inputs named alike would write one file in -o DIR/ or
    // --report DIR/: the second would replace the first.
    if (why.empty() && inputs.size() > 1 &&
        !(out.empty() && flags->report_page.empty())) {
      std::map<std::string, std::string> seen;
      for (const std::string& input : inputs) {
        const std::string stem = std::filesystem::path(input).stem().string();
        const auto [it, added] = seen.emplace(stem, input);
        if (!added) {
          why = "'" + it->second + "' and '" + input +
                "' would be written to one file (" + stem +
                ".*) in the output directory: fill them in separate runs";
          break;
        }
      }
    }
    for (const std::string& dir : {out, flags->report_page}) {
      if (!why.empty() || inputs.size() < 2 || dir.empty()) continue;
      std::error_code ec;
      std::filesystem::create_directories(dir, ec);
      if (ec) why = "cannot create directory '" + dir + "': " + ec.message();
    }
    if (!why.empty()) {
      if (flags->json) {
        std::string named;
        for (const std::string& i : flags->inputs) {
          named += (named.empty() ? "" : " ") + i;
        }
        std::cout << FillOutcomeJson(named, {}, "",
                                     error.empty() ? kOutcomeOutputError
                                                   : kOutcomeInputError,
                                     kExitUsage, why, false)
                  << std::endl;
      } else {
        std::cerr << "dotctl: fill-holes: " << why << "\n";
      }
      ctx->exit_code = std::max(ctx->exit_code, static_cast<int>(kExitUsage));
      return;
    }
    // One connection for every mesh sent to a server.
    Connection server;
    for (const std::string& input : inputs) {
      FillFlags one = *flags;
      one.input = input;
      FillOne(one, ctx, &server);
    }
  });
}

}  // namespace dot::client
