// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl's subcommands. Each Add*Command registers itself on the app; its
// callback stores the process exit code in ctx->exit_code.
#ifndef DOT_CLIENT_COMMANDS_H_
#define DOT_CLIENT_COMMANDS_H_

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "request_flags.h"

namespace CLI {
class App;
}

namespace dot::client {

struct Context {
  ConnectionFlags connection;
  int exit_code = 0;
  bool quiet = false;    // -q: errors only (and what --json asks for)
  bool verbose = false;  // -v: timing lines on stderr
};

void AddTriangulateCommand(CLI::App& app, Context* ctx);
void AddBatchCommand(CLI::App& app, Context* ctx);
void AddHealthCommand(CLI::App& app, Context* ctx);
void AddInfoCommands(CLI::App& app, Context* ctx);  // info, source
void AddLoadCommand(CLI::App& app, Context* ctx);
void AddGenerateCommand(CLI::App& app, Context* ctx);
void AddFillHolesCommand(CLI::App& app, Context* ctx);

// Shared helpers.

// Raises ctx->exit_code to `code`: the most serious outcome wins (2 and 3
// over 1), and 4 (no triangulation) only over 0.
void RaiseExitCode(Context* ctx, int code);
// "dotctl: <message>" on stderr, always (also with -q).
void PrintError(const std::string& message);
// "dotctl: <message>" on stderr with -v.
void PrintVerbose(const Context& ctx, const std::string& message);

// Polygon files named, or found (*.xyz, *.txt, *.obj) in a directory; "-"
// (stdin) and names that do not exist are passed through for the reader to
// report. Error: no polygon files at all.
std::vector<std::string> ExpandInputs(const std::vector<std::string>& args,
                                      std::string* error);
// "-", or a path that names a stream rather than a file (/dev/stdin,
// /dev/fd/N, /proc/self/fd/N, a pipe, a device): nothing can be written
// beside it.
bool IsStreamInput(const std::string& input);
// Reads one polygon: "-" from stdin, else the file. `format` (--input-format:
// "", "xyz"/"txt" or "obj") says how to read stdin and other streams
// (default plain text); files go by their extension (.obj is OBJ, anything
// else text).
// `notes` receives what the reader changed (a dropped closing vertex).
Status ReadPolygonInput(const std::string& input, const std::string& format,
                        PolygonData* out, std::vector<std::string>* notes);

// Where one mesh goes: stdout, or a file in a format.
struct OutputTarget {
  bool to_stdout = false;
  std::string path;    // the file (to_stdout: empty)
  std::string format;  // obj, ply or off
  std::string error;   // why the mesh could not be written there; "" if fine
  // As reports show it: the path, or "-".
  std::string Name() const { return to_stdout ? "-" : path; }
};
// Resolves, and checks before any work, where the mesh of `input` goes.
// `output` is the -o value: "" beside the input (NAME.tri.FORMAT; stdout for
// a stream input), "-" stdout, a directory (DIR/NAME.FORMAT) when
// `into_directory` or when it is one or ends with '/', else the file.
// `format` is --format: "" means from the extension (obj by default); with a
// file of no or an unknown extension it decides, and contradicting the
// extension is an error. The check: the format is known and the file can be
// created or overwritten (the directory exists and is writable), with the
// reason (strerror) in `error` when not.
OutputTarget ResolveOutput(const std::string& input, const std::string& output,
                           const std::string& format, bool into_directory);
// Writes the mesh (binary PLY for .ply) to stdout, or to a temporary file
// beside the target renamed over it once complete (a failure leaves nothing
// behind; devices and pipes are written in place). Returns "" or the error
// with its reason.
std::string WriteOutput(const OutputTarget& target, const MeshData& mesh);

// A file written through a temporary beside it and renamed over it by
// Commit, so a failed write leaves no partial (or 0-byte) file; "-" is
// stdout, and devices and pipes are written in place. Open reports (with
// the reason) what keeps the file from being written, before any work.
class AtomicOutput {
 public:
  AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  ~AtomicOutput();  // removes the temporary unless committed
  // "" or the error ("cannot write 'PATH': REASON").
  std::string Open(const std::string& path);
  std::ostream& stream();
  // Flushes, closes and renames into place: "" or the error.
  std::string Commit();

 private:
  class Buffer;
  std::string path_, temp_;
  int fd_ = -1;
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> stream_;
};

int ExitCodeFor(const grpc::Status& status);
// The channel to ctx->connection, or null after reporting a usage error.
std::shared_ptr<grpc::Channel> ChannelOrReport(Context* ctx);

}  // namespace dot::client

#endif  // DOT_CLIENT_COMMANDS_H_
