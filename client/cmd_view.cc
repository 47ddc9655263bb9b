// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl view MESH: a page to look at any mesh (a fill's result, a
// triangulation, a scan) in a browser, its holes listed. The holes are
// found in this process, as fill-holes --dry-run finds them.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "cli/json_envelope.h"
#include "commands.h"
#include "exit_codes.h"
#include "fill_call.h"
#include "remote_call.h"
#include "view_page.h"

namespace dot::client {
namespace {

struct ViewFlags {
  std::string input, output, input_format;
  bool json = false;
};

// NAME.html beside the input (stdout for a stream), or in the directory
// -o names.
std::string PagePath(const ViewFlags& f) {
  const std::string stem = IsStreamInput(f.input)
                               ? "stdin"
                               : std::filesystem::path(f.input).stem().string();
  std::error_code ec;
  if (f.output.empty()) {
    if (IsStreamInput(f.input)) return "-";
    return std::filesystem::path(f.input).replace_extension(".html").string();
  }
  if (f.output != "-" &&
      (f.output.back() == '/' || std::filesystem::is_directory(f.output, ec))) {
    std::filesystem::create_directories(f.output, ec);
    return (std::filesystem::path(f.output) / (stem + ".html")).string();
  }
  return f.output;
}

void View(const ViewFlags& f, Context* ctx) {
  JsonEnvelope e;
  e.input = f.input;
  const std::string path = PagePath(f);
  auto finish = [&](const char* outcome, int code, const std::string& error) {
    RaiseExitCode(ctx, code);
    e.outcome = outcome;
    e.exit_code = code;
    e.error = error;
    if (f.json) {
      (path == "-" ? std::cerr : std::cout) << e.ToJson() << std::endl;
    } else if (!error.empty()) {
      PrintError(f.input + ": " + error);
    }
  };
  if (SameFile(f.input, path)) {
    finish(kOutcomeOutputError, kExitUsage,
           "the page would overwrite the mesh: name another with -o");
    return;
  }
  AtomicOutput out;
  if (std::string error = out.Open(path); !error.empty()) {
    finish(kOutcomeOutputError, kExitUsage, error);
    return;
  }
  PolygonSoup soup;
  const Status read = ReadMeshInput(f.input, f.input_format, &soup, &e.notes);
  if (!read.ok()) {
    finish(kOutcomeInputError, kExitUsage, read.message);
    return;
  }
  // The holes, as a dry run lists them (repair on a copy: the page shows
  // the mesh as it is).
  v1::FillOptions options;
  options.set_dry_run(true);
  const FillOutcome listing = FillLocal(f.input, options, soup);
  e.fields = {{"report", listing.status.ok() ? ProtoJson(listing.report)
                                             : std::string("null")}};
  ViewPage page;
  page.title = f.input == "-" ? "stdin" : f.input;
  page.after = &soup;
  if (listing.status.ok()) {
    page.report = &listing.report;
    const v1::FillReport& r = listing.report;
    page.summary = std::to_string(soup.vertices.size()) + " vertices, " +
                   std::to_string(soup.faces.size()) + " faces; " +
                   std::to_string(r.loops()) +
                   (r.loops() == 1 ? " hole" : " holes") +
                   (r.loops() == 0 ? " (closed)" : "");
  } else {
    e.notes.push_back("holes not listed: " + listing.status.error_message());
    page.summary = std::to_string(soup.vertices.size()) + " vertices, " +
                   std::to_string(soup.faces.size()) + " faces";
  }
  std::string html;
  if (const Status s = RenderViewPage(page, &html); !s.ok()) {
    finish(kOutcomeInputError,
           s.code == StatusCode::kInvalidArgument ? kExitUsage : kExitFailed,
           s.message);
    return;
  }
  out.stream() << html;
  if (std::string error = out.Commit(); !error.empty()) {
    finish(kOutcomeWriteFailed, kExitFailed, error);
    return;
  }
  e.output = path;
  finish(kOutcomeOk, kExitOk, "");
  if (!f.json && !ctx->quiet && path != "-") {
    std::cout << f.input << ": " << page.summary << " -> " << path << "\n";
    for (const std::string& note : e.notes) {
      std::cout << "  note: " << note << "\n";
    }
  }
}

}  // namespace

void AddViewCommand(CLI::App& app, Context* ctx) {
  auto flags = std::make_shared<ViewFlags>();
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Write a page to look at a mesh in a browser (one HTML file, no "
      "network needed): the surface, its open edges, its holes listed.\n"
      "Example: dotctl view scan.ply -o scan.html");
  cmd->add_option("mesh", flags->input,
                  "the mesh (.off, .obj, .ply, .stl), or - for stdin (with "
                  "--input-format)")
      ->required();
  cmd->add_option("-o,--output", flags->output,
                  "the page (- for stdout, DIR/ for DIR/NAME.html); default: "
                  "NAME.html beside the mesh, stdout for a stream");
  cmd->add_option("--input-format", flags->input_format,
                  "format of a mesh read from stdin")
      ->check(CLI::IsMember({"off", "obj", "ply", "stl"}));
  cmd->add_flag("--json", flags->json,
                "the outcome as one JSON object on stdout (on stderr when "
                "the page goes to stdout)");
  cmd->callback([flags, ctx] { View(*flags, ctx); });
}

}  // namespace dot::client
