// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl batch DIR|FILES : every polygon over one TriangulateBatch stream;
// results are written as they arrive, with a progress bar on a terminal and
// a summary table at the end.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <thread>

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
    std::string output, format = "obj";
    RequestFlags request;
    bool json = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "Triangulate many polygons over one stream (all holes of a mesh, all "
      "patches of a sketch).\nExample: dotctl batch holes/ -o patches/");
  cmd->add_option("inputs", flags->inputs, "directories or polygon files")
      ->required();
  cmd->add_option("-o,--output", flags->output,
                  "directory for the meshes (default: beside each input)");
  cmd->add_option("--format", flags->format, "obj, ply or off")
      ->check(CLI::IsMember({"obj", "ply", "off"}))
      ->capture_default_str();
  cmd->add_flag("--json", flags->json, "one JSON object per input on stdout");
  AddRequestFlags(cmd, &flags->request);
  cmd->callback([flags, ctx] {
    std::string error;
    const auto files = ExpandInputs(flags->inputs, &error);
    if (!error.empty()) {
      std::cerr << "dotctl: " << error << "\n";
      ctx->exit_code = kExitUsage;
      return;
    }
    auto channel = ChannelOrReport(ctx);
    if (!channel) return;
    if (!flags->output.empty())
      std::filesystem::create_directories(flags->output);
    std::map<std::string, Pending> pending;
    std::vector<v1::TriangulateRequest> requests;
    for (const std::string& f : files) {
      PolygonData polygon;
      const Status s = ReadPolygonFile(f, &polygon);
      if (!s.ok()) {
        std::cerr << "dotctl: " << s.message << "\n";
        ctx->exit_code = kExitUsage;
        return;
      }
      requests.push_back(wire::MakeRequest(f, polygon, flags->request.weights,
                                           flags->request.ToOptions()));
      pending[f].input = std::move(polygon.vertices);
    }
    auto stub = v1::Triangulator::NewStub(channel);
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() +
                         std::chrono::seconds(static_cast<int64_t>(
                             ctx->connection.timeout_s * files.size())));
    auto stream = stub->TriangulateBatch(&context);
    const auto start = std::chrono::steady_clock::now();
    std::thread writer([&] {
      for (const auto& r : requests) {
        pending[r.id()].sent = std::chrono::steady_clock::now();
        if (!stream->Write(r)) break;
      }
      stream->WritesDone();
    });
    const bool tty = ::isatty(STDERR_FILENO) && !flags->json;
    std::vector<Row> rows;
    v1::TriangulateResponse msg;
    while (stream->Read(&msg)) {
      auto it = pending.find(msg.id());
      if (it == pending.end()) continue;
      Pending& p = it->second;
      if (msg.has_mesh()) {
        (void)p.assembler.Add(msg.mesh());
        continue;
      }
      CallOutcome out;
      out.latency_ms = std::chrono::duration<double, std::milli>(
                           std::chrono::steady_clock::now() - p.sent)
                           .count();
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
        continue;  // progress
      }
      Row row{msg.id(),      "", "", static_cast<uint32_t>(p.input.size()), 0,
              out.latency_ms};
      std::string path;
      if (out.status.ok() && out.summary.status() == v1::RESULT_STATUS_OK) {
        path = OutputPathFor(msg.id(), flags->output, flags->format,
                             !flags->output.empty());
        const Status w = WriteMeshFile(path, out.mesh);
        if (!w.ok()) out.status = {grpc::StatusCode::INTERNAL, w.message};
        row.triangles = out.summary.triangle_count();
      }
      if (!out.status.ok()) {
        row.status = std::string(wire::GrpcCodeName(out.status.error_code()));
        row.detail = out.status.error_message();
        ctx->exit_code = std::max(ctx->exit_code, ExitCodeFor(out.status));
      } else if (out.summary.status() != v1::RESULT_STATUS_OK) {
        row.status = "NO_TRIANGULATION";
        row.detail = out.summary.message();
        if (ctx->exit_code == kExitOk) ctx->exit_code = kExitNoTriangulation;
      } else {
        row.status = "OK";
        row.detail = out.summary.solver() + ", cost " +
                     std::to_string(out.summary.total_cost()) + " -> " + path;
      }
      if (flags->json)
        std::cout << OutcomeJson(msg.id(), out, path) << std::endl;
      rows.push_back(std::move(row));
      pending.erase(it);
      if (tty) DrawBar(rows.size(), files.size());
    }
    writer.join();
    const grpc::Status status = stream->Finish();
    if (tty) std::fprintf(stderr, "\n");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    if (!flags->json) {
      std::printf("%-40s %8s %9s %9s  %-18s %s\n", "input", "vertices",
                  "triangles", "ms", "status", "detail");
      for (const Row& r : rows) {
        std::printf("%-40s %8u %9u %9.1f  %-18s %s\n", r.file.c_str(), r.n,
                    r.triangles, r.ms, r.status.c_str(), r.detail.c_str());
      }
      std::printf("%zu of %zu polygons answered in %.2f s\n", rows.size(),
                  files.size(), seconds);
    }
    if (!status.ok()) {
      std::cerr << "dotctl: batch stream failed: "
                << wire::GrpcCodeName(status.error_code()) << ": "
                << status.error_message() << "\n";
      ctx->exit_code = std::max(ctx->exit_code, ExitCodeFor(status));
    } else if (rows.size() != files.size()) {
      ctx->exit_code = std::max(ctx->exit_code, int{kExitFailed});
    }
  });
}

}  // namespace dot::client
