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
double MsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string Ms(double ms) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f ms", ms);
  return buf;
}

std::string LowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty()) ext = ext.substr(1);
  for (char& c : ext) c = static_cast<char>(std::tolower(c));
  return ext;
}

bool IsMeshFormat(const std::string& f) {
  return f == "obj" || f == "ply" || f == "off";
}

std::string CannotWrite(const std::string& path, int error) {
  return "cannot write '" + path + "': " + std::strerror(error);
}

}  // namespace

void RaiseExitCode(Context* ctx, int code) {
  if (code == kExitOk) return;
  if (code == kExitNoTriangulation) {
    if (ctx->exit_code == kExitOk) ctx->exit_code = code;
    return;
  }
  const int now = ctx->exit_code == kExitNoTriangulation ? 0 : ctx->exit_code;
  ctx->exit_code = std::max(now, code);
}

void PrintError(const std::string& message) {
  std::cout.flush();
  std::cerr << "dotctl: " << message << std::endl;
}

void PrintVerbose(const Context& ctx, const std::string& message) {
  if (ctx.verbose) std::cerr << "dotctl: " << message << std::endl;
}

std::vector<std::string> ExpandInputs(const std::vector<std::string>& args,
                                      std::string* error) {
  std::vector<std::string> files;
  for (const std::string& a : args) {
    std::error_code ec;
    if (a != "-" && fs::is_directory(a, ec)) {
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
    } else {
      files.push_back(a);  // "-", a file, or a name the reader will refuse
    }
  }
  if (files.empty() && error->empty()) *error = "no polygon files found";
  return files;
}

bool IsStreamInput(const std::string& input) {
  // /dev/stdin and /proc/self/fd/0 resolve to a regular file when stdin is
  // redirected from one: known by name.
  if (input == "-" || input == "/dev/stdin" ||
      input.rfind("/dev/fd/", 0) == 0 ||
      (input.rfind("/proc/", 0) == 0 &&
       input.find("/fd/") != std::string::npos)) {
    return true;
  }
  struct stat st;
  return ::stat(input.c_str(), &st) == 0 && !S_ISREG(st.st_mode) &&
         !S_ISDIR(st.st_mode);
}

Status ReadPolygonInput(const std::string& input, const std::string& format,
                        PolygonData* out, std::vector<std::string>* notes) {
  if (input != "-" && (format.empty() || !IsStreamInput(input))) {
    return ReadPolygonFile(input, out, notes);
  }
  const bool obj = format == "obj";
  Status s;
  if (input == "-") {
    s = obj ? ReadPolygonObj(std::cin, out, notes)
            : ReadPolygonText(std::cin, out, notes);
    if (!s.ok()) s.message = "stdin: " + s.message;
    return s;
  }
  errno = 0;
  std::ifstream in(input);
  if (!in) {
    return InvalidArgument(
        "cannot open polygon file '" + input + "'" +
        (errno ? std::string(": ") + std::strerror(errno) : std::string()));
  }
  s = obj ? ReadPolygonObj(in, out, notes) : ReadPolygonText(in, out, notes);
  if (!s.ok()) s.message = input + ": " + s.message;
  return s;
}

OutputTarget ResolveOutput(const std::string& input, const std::string& output,
                           const std::string& format, bool into_directory) {
  OutputTarget t;
  const std::string fmt = format.empty() ? "obj" : format;
  if (output == "-" || (output.empty() && IsStreamInput(input))) {
    t.to_stdout = true;
    t.format = fmt;
    return t;
  }
  const std::string stem =
      input == "-" ? "stdin" : fs::path(input).stem().string();
  std::error_code ec;
  if (output.empty()) {
    t.format = fmt;
    t.path = (fs::path(input).parent_path() / (stem + ".tri." + fmt)).string();
  } else if (into_directory || output.back() == '/' ||
             fs::is_directory(output, ec)) {
    t.format = fmt;
    t.path = (fs::path(output) / (stem + "." + fmt)).string();
  } else {
    t.path = output;
    const std::string ext = LowerExtension(output);
    if (IsMeshFormat(ext)) {
      if (!format.empty() && format != ext) {
        t.error = "-o '" + output + "' names a ." + ext +
                  " file but --format says " + format;
      }
      t.format = ext;
    } else if (!format.empty()) {
      t.format = format;
    } else {
      t.error = "cannot tell the mesh format of '" + output +
                "'; name it .obj, .ply or .off, or give --format";
    }
  }
  if (t.error.empty() && fs::is_directory(t.path, ec)) {
    t.error = CannotWrite(t.path, EISDIR);
  }
  return t;
}

// An ostream buffer over a file descriptor that keeps the errno of a
// failed write.
class AtomicOutput::Buffer : public std::streambuf {
 public:
  explicit Buffer(int fd) : fd_(fd) { setp(data_, data_ + sizeof data_); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!Drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return Drain() ? 0 : -1; }

 private:
  bool Drain() {
    const char* p = pbase();
    while (p < pptr() && error_ == 0) {
      const ssize_t n = ::write(fd_, p, static_cast<size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        error_ = n < 0 ? errno : EIO;
        break;
      }
      p += n;
    }
    setp(data_, data_ + sizeof data_);
    return error_ == 0;
  }
  int fd_;
  int error_ = 0;
  char data_[1 << 16];
};

AtomicOutput::AtomicOutput() = default;

AtomicOutput::~AtomicOutput() {
  stream_.reset();
  buffer_.reset();
  if (fd_ > STDERR_FILENO) ::close(fd_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

std::string AtomicOutput::Open(const std::string& path) {
  path_ = path;
  if (path == "-") {
    std::cout.flush();
    fd_ = STDOUT_FILENO;
  } else {
    struct stat st;
    const bool exists = ::stat(path.c_str(), &st) == 0;
    if (!exists && errno != ENOENT) return CannotWrite(path, errno);
    if (exists && S_ISDIR(st.st_mode)) return CannotWrite(path, EISDIR);
    if (exists && !S_ISREG(st.st_mode)) {
      // A device or a pipe: written in place, nothing to rename.
      fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
      if (fd_ < 0) return CannotWrite(path, errno);
    } else {
      if (exists && ::access(path.c_str(), W_OK) != 0) {
        return CannotWrite(path, errno);
      }
      const fs::path p(path);
      const fs::path dir = p.has_parent_path() ? p.parent_path() : ".";
      std::string temp =
          (dir / ("." + p.filename().string() + ".XXXXXX")).string();
      fd_ = ::mkstemp(temp.data());
      if (fd_ < 0) return CannotWrite(path, errno);
      temp_ = temp;
      mode_t mode;
      if (exists) {
        mode = st.st_mode & 07777;
      } else {
        const mode_t mask = ::umask(0);
        ::umask(mask);
        mode = 0666 & ~mask;
      }
      (void)::fchmod(fd_, mode);
    }
  }
  buffer_ = std::make_unique<Buffer>(fd_);
  stream_ = std::make_unique<std::ostream>(buffer_.get());
  return "";
}

std::ostream& AtomicOutput::stream() { return *stream_; }

std::string AtomicOutput::Commit() {
  stream_->flush();
  if (buffer_->error() != 0) return CannotWrite(path_, buffer_->error());
  if (!*stream_) return CannotWrite(path_, EIO);
  if (fd_ > STDERR_FILENO) {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) return CannotWrite(path_, errno);
  }
  if (!temp_.empty()) {
    if (::rename(temp_.c_str(), path_.c_str()) != 0) {
      return CannotWrite(path_, errno);
    }
    temp_.clear();
  }
  return "";
}

std::string WriteOutput(const OutputTarget& target, const MeshData& mesh) {
  AtomicOutput out;
  std::string error = out.Open(target.Name());
  if (!error.empty()) return error;
  const Status s = WriteMesh(out.stream(), target.format, mesh);
  error = out.Commit();
  if (error.empty() && !s.ok()) error = s.message;
  return error;
}

std::shared_ptr<grpc::Channel> ChannelOrReport(Context* ctx) {
  std::string error;
  auto channel = MakeChannel(ctx->connection, &error);
  if (!channel) {
    PrintError(error);
    RaiseExitCode(ctx, kExitUsage);
    return nullptr;
  }
  char timeout[32];
  std::snprintf(timeout, sizeof timeout, "%g", ctx->connection.timeout_s);
  PrintVerbose(
      *ctx, "server " + ctx->connection.server +
                (ctx->connection.tls_ca.empty() ? " (plaintext)" : " (TLS)") +
                ", deadline " + timeout + " s a call");
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
    std::string output, format, input_format;
    RequestFlags request;
    bool json = false, local = false, progress = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "triangulate",
      "Triangulate polygon files (x y z lines, or OBJ v/l) into meshes.\n"
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
                  "obj, ply or off: for stdout, directories and -o names "
                  "without a mesh extension (default obj)")
      ->check(CLI::IsMember({"obj", "ply", "off"}));
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
               (fs::exists(output) || IsMeshFormat(LowerExtension(output)))) {
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
    std::shared_ptr<grpc::Channel> channel;
    std::unique_ptr<v1::Triangulator::Stub> stub;
    std::unique_ptr<DelaunayHelperPool> helpers;
    if (!flags->local) {
      channel = ChannelOrReport(ctx);
      if (!channel) return;
      stub = v1::Triangulator::NewStub(channel);
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
                : TriangulateRemote(
                      *stub, request, polygon.vertices,
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
