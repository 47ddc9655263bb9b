// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl batch DIR|FILES : every polygon over one TriangulateBatch stream;
// results are written as they arrive, with a progress bar on a terminal and
// a summary table at the end.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>

#include "commands.h"
#include "exit_codes.h"
#include "remote_call.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

struct Pending {
  std::vector<Vec3> input;
  wire::MeshAssembler assembler;
  std::chrono::steady_clock::time_point sent;
};

struct Row {
  std::string file, status, detail;
  uint32_t n = 0, triangles = 0;
  double ms = 0;
};

void DrawBar(size_t done, size_t total) {
  const int width = 40;
  const int filled = total ? static_cast<int>(width * done / total) : width;
  std::fprintf(stderr, "\r[%s%s] %zu/%zu", std::string(filled, '#').c_str(),
               std::string(width - filled, '.').c_str(), done, total);
  std::fflush(stderr);
}

}  // namespace

void AddBatchCommand(CLI::App& app, Context* ctx) {
  struct Flags {
    std::vector<std::string> inputs;
    std::string output, format = "obj", input_format;
    RequestFlags request;
    bool json = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "Triangulate many polygons over one stream (all holes of a mesh, all "
      "patches of a sketch).\nExample: dotctl batch holes/ -o patches/");
  cmd->add_option("inputs", flags->inputs,
                  "directories or polygon files; - reads one polygon from "
                  "stdin (needs -o DIR: its mesh is DIR/stdin.FORMAT)")
      ->required();
  cmd->add_option("-o,--output", flags->output,
                  "directory for the meshes (default: beside each input)");
  cmd->add_option("--format", flags->format, "obj, ply, off or stl")
      ->check(CLI::IsMember({"obj", "ply", "off", "stl"}))
      ->capture_default_str();
  cmd->add_option("--input-format", flags->input_format,
                  "xyz (plain text, the default) or obj: how to read a "
                  "polygon from stdin; files go by their extension")
      ->check(CLI::IsMember({"xyz", "txt", "obj"}));
  cmd->add_flag("--json", flags->json,
                "one JSON object per input (as triangulate's) on stdout");
  AddRequestFlags(cmd, &flags->request);
  cmd->callback([flags, ctx] {
    std::string error;
    const auto named = ExpandInputs(flags->inputs, &error);
    if (error.empty() && std::count(named.begin(), named.end(), "-") > 1) {
      error = "stdin can be read once: give - once";
    }
    // The stream's answers are keyed by input: each is sent once.
    std::vector<std::string> dropped;
    const auto files = EachOnce(named, &dropped);
    for (const std::string& again : dropped) {
      if (!ctx->quiet) {
        std::cerr << "dotctl: note: " << again
                  << " is named more than once: sent once\n";
      }
    }
    if (error.empty() && flags->output.empty() &&
        std::any_of(files.begin(), files.end(), IsStreamInput)) {
      error = "a polygon read from a stream needs -o DIR for its mesh";
    }
    if (!error.empty()) {
      PrintError(error);
      RaiseExitCode(ctx, kExitUsage);
      return;
    }
    std::string directory_error;
    if (!flags->output.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(flags->output, ec);
      if (ec) {
        directory_error =
            "cannot create directory '" + flags->output + "': " + ec.message();
      }
    }
    const auto report_one = [&](InputReport& report) {
      if (report.outcome == kOutcomeInputError) {
        PrintError(report.error);  // names the input already
      } else if (!report.error.empty() &&
                 report.outcome != kOutcomeNoTriangulation) {
        PrintError(report.input + ": " + report.error);
      }
      if (!ctx->quiet) {
        for (const std::string& note : report.notes) {
          std::cerr << "dotctl: " << report.input << ": note: " << note << "\n";
        }
      }
      if (flags->json) std::cout << ReportJson(report) << std::endl;
      RaiseExitCode(ctx, report.exit_code);
    };
    // Every input read, and its output checked, before anything is sent.
    std::map<std::string, Pending> pending;
    std::map<std::string, OutputTarget> targets;
    std::map<std::string, std::vector<std::string>> notes;
    std::map<std::string, std::vector<Vec3>> normals;
    std::vector<v1::TriangulateRequest> requests;
    for (const std::string& f : files) {
      InputReport report;
      report.input = f;
      PolygonData polygon;
      const Status s =
          ReadPolygonInput(f, flags->input_format, &polygon, &report.notes);
      if (!s.ok()) {
        report.outcome = kOutcomeInputError;
        report.error = s.message;
        report.exit_code = kExitUsage;
        report_one(report);
        continue;
      }
      OutputTarget target = ResolveOutput(f, flags->output, flags->format,
                                          !flags->output.empty());
      if (!directory_error.empty()) target.error = directory_error;
      if (target.error.empty()) {
        // The real check: a temporary file beside the target, removed here.
        AtomicOutput probe;
        target.error = probe.Open(target.Name());
      }
      if (!target.error.empty()) {
        report.outcome = kOutcomeOutputError;
        report.error = target.error;
        report.exit_code = kExitUsage;
        report_one(report);
        continue;
      }
      targets[f] = target;
      notes[f] = std::move(report.notes);
      normals[f] = polygon.normals;
      requests.push_back(wire::MakeRequest(f, polygon, flags->request.weights,
                                           flags->request.ToOptions()));
      pending[f].input = std::move(polygon.vertices);
    }
    if (requests.empty()) return;
    const Connection server = ConnectOrReport(ctx, flags->json);
    if (!server) return;
    const auto start = std::chrono::steady_clock::now();
    const bool tty = ::isatty(STDERR_FILENO) && !flags->json && !ctx->quiet;
    std::vector<Row> rows;
    // `pending` is shared with the stream's writer thread (`next`).
    std::mutex pending_mutex;
    size_t written = 0;
    const auto next = [&]() -> const v1::TriangulateRequest* {
      if (written == requests.size()) return nullptr;
      const v1::TriangulateRequest& r = requests[written++];
      std::lock_guard<std::mutex> lock(pending_mutex);
      const auto it = pending.find(r.id());
      if (it != pending.end())
        it->second.sent = std::chrono::steady_clock::now();
      return &r;
    };
    const auto on_answer = [&](const v1::TriangulateResponse& msg) {
      // The writer touches an entry's `sent` alone: read under the lock.
      std::map<std::string, Pending>::iterator it;
      std::chrono::steady_clock::time_point sent;
      {
        std::lock_guard<std::mutex> lock(pending_mutex);
        it = pending.find(msg.id());
        if (it == pending.end()) return;
        sent = it->second.sent;
      }
      Pending& p = it->second;
      if (msg.has_mesh()) {
        (void)p.assembler.Add(msg.mesh());
        return;
      }
      CallOutcome out;
      out.latency_ms = MsSince(sent);
      if (msg.has_error()) {
        out.status =
            grpc::Status(static_cast<grpc::StatusCode>(msg.error().code()),
                         msg.error().message());
      } else if (msg.has_summary()) {
        out.summary = msg.summary();
        if (out.summary.status() == v1::RESULT_STATUS_OK) {
          const Status s = p.assembler.Finish(out.summary, p.input, &out.mesh);
          if (!s.ok()) out.status = {grpc::StatusCode::DATA_LOSS, s.message};
        }
      } else {
        return;  // progress
      }
      PrintVerbose(*ctx, msg.id() + ": " + DescribeTiming(out));
      InputReport report;
      report.input = msg.id();
      report.call = &out;
      report.notes = std::move(notes[msg.id()]);
      Row row{msg.id(),      "", "", static_cast<uint32_t>(p.input.size()), 0,
              out.latency_ms};
      if (!out.status.ok()) {
        report.outcome = kOutcomeCallFailed;
        report.error =
            std::string(wire::GrpcCodeName(out.status.error_code())) + ": " +
            out.status.error_message();
        report.exit_code = ExitCodeFor(out.status);
        row.status = std::string(wire::GrpcCodeName(out.status.error_code()));
        row.detail = out.status.error_message();
      } else if (out.summary.status() != v1::RESULT_STATUS_OK) {
        report.outcome = kOutcomeNoTriangulation;
        report.error = out.summary.message();
        report.exit_code = kExitNoTriangulation;
        row.status = "NO_TRIANGULATION";
        row.detail = out.summary.message();
      } else {
        CheckOrientation(out.mesh, normals[msg.id()], &report);
        const OutputTarget& target = targets[msg.id()];
        const std::string w = WriteOutput(target, out.mesh);
        row.triangles = out.summary.triangle_count();
        if (w.empty()) {
          report.output = target.Name();
          row.status = "OK";
          row.detail = out.summary.solver() + ", cost " +
                       std::to_string(out.summary.total_cost()) + " -> " +
                       target.Name();
          if (report.OrientationContradictsNormals()) {
            row.detail +=
                "; WARNING: " + std::to_string(report.faces_against_normals) +
                " triangles face against the given normals";
          }
        } else {
          report.outcome = kOutcomeWriteFailed;
          report.error = w;
          report.exit_code = kExitFailed;
          row.status = "WRITE_FAILED";
          row.detail = w;
        }
      }
      report_one(report);
      rows.push_back(std::move(row));
      {
        std::lock_guard<std::mutex> lock(pending_mutex);
        pending.erase(it);
      }
      if (tty) DrawBar(rows.size(), requests.size());
    };
    const grpc::Status status = server.calls->batch(
        server.channel,
        std::chrono::system_clock::now() +
            std::chrono::seconds(static_cast<int64_t>(
                ctx->connection.timeout_s * requests.size())),
        next, on_answer, nullptr);
    if (tty) std::fprintf(stderr, "\n");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    if (!flags->json && !ctx->quiet) {
      std::printf("%-40s %8s %9s %9s  %-18s %s\n", "input", "vertices",
                  "triangles", "ms", "status", "detail");
      for (const Row& r : rows) {
        std::printf("%-40s %8u %9u %9.1f  %-18s %s\n", r.file.c_str(), r.n,
                    r.triangles, r.ms, r.status.c_str(), r.detail.c_str());
      }
      std::printf("%zu of %zu polygons answered in %.2f s\n", rows.size(),
                  requests.size(), seconds);
      std::fflush(stdout);
    }
    // The inputs the stream never answered get their report too.
    const grpc::Status lost =
        status.ok() ? grpc::Status(grpc::StatusCode::DATA_LOSS,
                                   "the stream ended without an answer")
                    : status;
    for (const auto& r : requests) {
      if (pending.count(r.id()) == 0) continue;
      CallOutcome out;
      out.status = lost;
      InputReport report;
      report.input = r.id();
      report.call = &out;
      report.outcome = kOutcomeCallFailed;
      report.error = std::string(wire::GrpcCodeName(lost.error_code())) + ": " +
                     lost.error_message();
      report.exit_code = ExitCodeFor(lost);
      if (flags->json) {
        report_one(report);
      } else {
        RaiseExitCode(ctx, report.exit_code);
      }
    }
    if (!status.ok()) {
      PrintError("batch stream failed: " +
                 std::string(wire::GrpcCodeName(status.error_code())) + ": " +
                 status.error_message());
      RaiseExitCode(ctx, ExitCodeFor(status));
    }
  });
}

}  // namespace dot::client
