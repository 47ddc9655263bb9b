// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl triangulate FILE... : one Triangulate call per file (or the core
// in-process with --local), a mesh file and a summary line per input.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <streambuf>

#include "commands.h"
#include "exit_codes.h"
#include "remote_call.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;
std::string Ms(double ms) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f ms", ms);
  return buf;
}

}  // namespace

void AddTriangulateCommand(CLI::App& app, Context* ctx) {
  struct Flags {
    std::vector<std::string> inputs;
    std::string output, format, input_format;
    RequestFlags request;
    bool json = false, local = false, progress = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "triangulate",
      "Triangulate polygon files (x y z lines, or OBJ v/l) into meshes. A\n"
      "file with several loops (blocks of lines separated by blank lines, or\n"
      "'l' lines closing into several loops) becomes one surface joining\n"
      "them (two loops exactly; three or more by bridges first, an\n"
      "approximation, each loop keeping its direction).\n"
      "Example: dotctl triangulate hole.xyz -o patch.obj --squared-dihedral 1");
  cmd->add_option("files", flags->inputs,
                  "polygon files or directories; - reads one polygon from "
                  "stdin (its mesh then goes to stdout unless -o says)")
      ->required();
  cmd->add_option("-o,--output", flags->output,
                  "mesh file (one input) or directory (several, or a name "
                  "ending in /); - for stdout; format from the extension: "
                  ".obj, .ply, .off");
  cmd->add_option("--format", flags->format,
                  "obj, ply, off or stl: for stdout, directories and -o names "
                  "without a mesh extension (default obj)")
      ->check(CLI::IsMember({"obj", "ply", "off", "stl"}));
  cmd->add_option("--input-format", flags->input_format,
                  "xyz (plain text, the default) or obj: how to read a "
                  "polygon from stdin (- or /dev/stdin); files go by their "
                  "extension")
      ->check(CLI::IsMember({"xyz", "txt", "obj"}));
  cmd->add_flag("--json", flags->json,
                "one JSON object per input (version 1, see the README) on "
                "stdout, or on stderr when the mesh goes to stdout");
  cmd->add_flag("--local", flags->local,
                "run the triangulation in this process, no server needed");
  cmd->add_flag("--progress", flags->progress,
                "print progress of long runs to stderr");
  AddRequestFlags(cmd, &flags->request);
  cmd->callback([flags, ctx] {
    std::string error;
    const auto files = ExpandInputs(flags->inputs, &error);
    if (!error.empty()) {
      PrintError(error);
      RaiseExitCode(ctx, kExitUsage);
      return;
    }
    const bool many = files.size() > 1;
    const std::string& output = flags->output;
    if (std::count(files.begin(), files.end(), "-") > 1) {
      error = "stdin can be read once: give - once";
    } else if (output == "-" && many) {
      error = "-o - writes one mesh to stdout: give one input, or -o DIR";
    } else if (many && output.empty() &&
               std::any_of(files.begin(), files.end(), IsStreamInput)) {
      error =
          "the mesh of a polygon read from a stream goes to stdout, which "
          "takes one input: give it alone, or -o DIR";
    } else if (many && !output.empty() && output.back() != '/' &&
               !fs::is_directory(output) &&
               (fs::exists(output) || NamesMeshFile(output))) {
      error = "-o '" + output + "' names a file, but " +
              std::to_string(files.size()) +
              " inputs need a directory for their meshes";
    }
    if (!error.empty()) {
      PrintError(error);
      RaiseExitCode(ctx, kExitUsage);
      return;
    }
    std::string directory_error;
    if (many && !output.empty()) {
      std::error_code ec;
      fs::create_directories(output, ec);
      if (ec) {
        directory_error =
            "cannot create directory '" + output + "': " + ec.message();
      }
    }
    // The mesh goes to stdout: the reports go to stderr.
    const bool mesh_to_stdout =
        output == "-" || (output.empty() && !many && IsStreamInput(files[0]));
    std::ostream& text = mesh_to_stdout ? std::cerr : std::cout;
    Connection server;
    std::unique_ptr<DelaunayHelperPool> helpers;
    if (!flags->local) {
      server = ConnectOrReport(ctx, flags->json);
      if (!server) return;
    } else if (flags->request.delaunay == "tetgen") {
      helpers = LocalDelaunayHelpers(1);
    }
    v1::Options options = flags->request.ToOptions();
    if (flags->progress) options.set_progress_interval_ms(250);
    for (const std::string& file : files) {
      InputReport report;
      report.input = file;
      CallOutcome out;
      const auto emit = [&] {
        const std::string name = file == "-" ? "stdin" : file;
        if (report.outcome == kOutcomeInputError) {
          PrintError(report.error);  // names the input already
        } else if (!report.error.empty() &&
                   report.outcome != kOutcomeNoTriangulation) {
          PrintError(name + ": " + report.error);
        }
        if (!ctx->quiet) {
          for (const std::string& note : report.notes) {
            std::cerr << "dotctl: " << name << ": note: " << note << "\n";
          }
        }
        if (flags->json) {
          text << ReportJson(report) << std::endl;
        } else if (!ctx->quiet && (report.outcome == kOutcomeOk ||
                                   report.outcome == kOutcomeNoTriangulation)) {
          text << name << ": " << DescribeReport(report) << std::endl;
        }
        RaiseExitCode(ctx, report.exit_code);
      };
      auto t0 = Clock::now();
      PolygonData polygon;
      const Status read =
          ReadPolygonInput(file, flags->input_format, &polygon, &report.notes);
      if (!read.ok()) {
        report.outcome = kOutcomeInputError;
        report.error = read.message;
        report.exit_code = kExitUsage;
        emit();
        continue;
      }
      PrintVerbose(*ctx, file + ": read " +
                             std::to_string(polygon.vertices.size()) +
                             " vertices" +
                             (polygon.normals.empty() ? "" : " with normals") +
                             " in " + Ms(MsSince(t0)));
      // Checked before the work: where the mesh goes, and that it can.
      OutputTarget target =
          ResolveOutput(file, output, flags->format, many && !output.empty());
      if (!directory_error.empty()) target.error = directory_error;
      AtomicOutput sink;
      if (target.error.empty()) target.error = sink.Open(target.Name());
      if (!target.error.empty()) {
        report.outcome = kOutcomeOutputError;
        report.error = target.error;
        report.exit_code = kExitUsage;
        emit();
        continue;
      }
      const auto request =
          wire::MakeRequest(file, polygon, flags->request.weights, options);
      out = flags->local
                ? TriangulateLocal(request, helpers.get())
                : server.calls->triangulate(
                      server.channel, request, polygon.vertices,
                      ctx->connection.timeout_s, [](const v1::Progress& p) {
                        std::cerr << "  " << v1::Stage_Name(p.stage()) << " "
                                  << static_cast<int>(100 * p.fraction())
                                  << "% after " << p.elapsed_ms() << " ms\n";
                      });
      report.call = &out;
      PrintVerbose(*ctx, file + ": " + DescribeTiming(out));
      if (!out.status.ok()) {
        report.outcome = kOutcomeCallFailed;
        report.error =
            std::string(wire::GrpcCodeName(out.status.error_code())) + ": " +
            out.status.error_message();
        report.exit_code = ExitCodeFor(out.status);
      } else if (out.summary.status() != v1::RESULT_STATUS_OK) {
        report.outcome = kOutcomeNoTriangulation;
        report.error = out.summary.message();
        report.exit_code = kExitNoTriangulation;
      } else {
        CheckOrientation(out.mesh, polygon.normals, &report);
        t0 = Clock::now();
        const Status w = WriteMesh(sink.stream(), target.format, out.mesh);
        std::string written = sink.Commit();
        if (written.empty() && !w.ok()) written = w.message;
        if (written.empty()) {
          report.output = target.Name();
          PrintVerbose(*ctx, file + ": wrote " + target.Name() + " (" +
                                 target.format + ") in " + Ms(MsSince(t0)));
        } else {
          report.outcome = kOutcomeWriteFailed;
          report.error = written;
          report.exit_code = kExitFailed;
        }
      }
      emit();
    }
  });
}

}  // namespace dot::client
