// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl triangulate FILE... : one Triangulate call per file (or the core
// in-process with --local), a mesh file and a summary line per input.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "exit_codes.h"
#include "remote_call.h"
#include "wire/wire.h"

namespace dot::client {

std::vector<std::string> ExpandInputs(const std::vector<std::string>& args,
                                      std::string* error) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const std::string& a : args) {
    std::error_code ec;
    if (fs::is_directory(a, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(a, ec)) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() &&
            (ext == ".xyz" || ext == ".txt" || ext == ".obj")) {
          found.push_back(e.path().string());
        }
      }
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::exists(a, ec)) {
      files.push_back(a);
    } else {
      *error = "no such file or directory: '" + a + "'";
      return {};
    }
  }
  if (files.empty() && error->empty()) *error = "no polygon files found";
  return files;
}

std::string OutputPathFor(const std::string& input, const std::string& output,
                          const std::string& format, bool many) {
  namespace fs = std::filesystem;
  const fs::path in(input);
  if (output.empty()) {
    return (in.parent_path() / (in.stem().string() + ".tri." + format))
        .string();
  }
  if (!many) return output;
  return (fs::path(output) / (in.stem().string() + "." + format)).string();
}

std::shared_ptr<grpc::Channel> ChannelOrReport(Context* ctx) {
  std::string error;
  auto channel = MakeChannel(ctx->connection, &error);
  if (!channel) {
    std::cerr << "dotctl: " << error << "\n";
    ctx->exit_code = kExitUsage;
  }
  return channel;
}

int ExitCodeFor(const grpc::Status& status) {
  switch (status.error_code()) {
    case grpc::StatusCode::OK:
      return kExitOk;
    case grpc::StatusCode::UNAVAILABLE:
      return kExitUnavailable;
    default:
      return kExitFailed;
  }
}

void AddTriangulateCommand(CLI::App& app, Context* ctx) {
  struct Flags {
    std::vector<std::string> inputs;
    std::string output, format;
    RequestFlags request;
    bool json = false, local = false, progress = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "triangulate",
      "Triangulate polygon files (x y z lines, or OBJ v/l) into meshes.\n"
      "Example: dotctl triangulate hole.xyz -o patch.obj --squared-dihedral 1");
  cmd->add_option("files", flags->inputs, "polygon files or directories")
      ->required();
  cmd->add_option("-o,--output", flags->output,
                  "mesh file (one input) or directory (several); format from "
                  "the extension: .obj, .ply, .off");
  cmd->add_option("--format", flags->format,
                  "obj, ply or off when -o does not say (default obj)")
      ->check(CLI::IsMember({"obj", "ply", "off"}));
  cmd->add_flag("--json", flags->json, "one JSON object per input on stdout");
  cmd->add_flag("--local", flags->local,
                "run the triangulation in this process, no server needed");
  cmd->add_flag("--progress", flags->progress,
                "print progress of long runs to stderr");
  AddRequestFlags(cmd, &flags->request);
  cmd->callback([flags, ctx] {
    std::string error;
    const auto files = ExpandInputs(flags->inputs, &error);
    if (!error.empty()) {
      std::cerr << "dotctl: " << error << "\n";
      ctx->exit_code = kExitUsage;
      return;
    }
    const bool many = files.size() > 1;
    std::string format = flags->format;
    if (format.empty()) {
      const std::string ext =
          std::filesystem::path(flags->output).extension().string();
      format =
          (!many && (ext == ".ply" || ext == ".off")) ? ext.substr(1) : "obj";
    }
    if (many && !flags->output.empty()) {
      std::filesystem::create_directories(flags->output);
    }
    std::shared_ptr<grpc::Channel> channel;
    std::unique_ptr<v1::Triangulator::Stub> stub;
    if (!flags->local) {
      channel = ChannelOrReport(ctx);
      if (!channel) return;
      stub = v1::Triangulator::NewStub(channel);
    }
    v1::Options options = flags->request.ToOptions();
    if (flags->progress) options.set_progress_interval_ms(250);
    for (const std::string& file : files) {
      PolygonData polygon;
      const Status read = ReadPolygonFile(file, &polygon);
      if (!read.ok()) {
        std::cerr << "dotctl: " << read.message << "\n";
        ctx->exit_code = kExitUsage;
        continue;
      }
      const auto request =
          wire::MakeRequest(file, polygon, flags->request.weights, options);
      const CallOutcome out =
          flags->local
              ? TriangulateLocal(request)
              : TriangulateRemote(
                    *stub, request, polygon.vertices, ctx->connection.timeout_s,
                    [](const v1::Progress& p) {
                      std::cerr << "  " << v1::Stage_Name(p.stage()) << " "
                                << static_cast<int>(100 * p.fraction())
                                << "% after " << p.elapsed_ms() << " ms\n";
                    });
      std::string path;
      if (out.status.ok() && out.summary.status() == v1::RESULT_STATUS_OK) {
        path = OutputPathFor(file, flags->output, format, many);
        const Status w = WriteMeshFile(path, out.mesh);
        if (!w.ok()) {
          std::cerr << "dotctl: " << w.message << "\n";
          ctx->exit_code = kExitFailed;
          path.clear();
        }
      }
      if (flags->json) {
        std::cout << OutcomeJson(file, out, path) << std::endl;
      } else {
        std::cout << file << ": " << DescribeOutcome(out)
                  << (path.empty() ? "" : " -> " + path) << std::endl;
      }
      if (!out.status.ok()) {
        ctx->exit_code = std::max(ctx->exit_code, ExitCodeFor(out.status));
      } else if (out.summary.status() != v1::RESULT_STATUS_OK &&
                 ctx->exit_code == kExitOk) {
        ctx->exit_code = kExitNoTriangulation;
      }
    }
  });
}

}  // namespace dot::client
