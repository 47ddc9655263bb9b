// SPDX-License-Identifier: AGPL-3.0-or-later
// Where dotctl's results go, checked before any work, and written so that
// a failure leaves no partial file.
#ifndef DOT_CLIENT_CLI_OUTPUT_H_
#define DOT_CLIENT_CLI_OUTPUT_H_

#include <memory>
#include <ostream>
#include <string>

#include "dot/dot.h"

namespace dot::client {

// Where one mesh goes: stdout, or a file in a format.
struct OutputTarget {
  bool to_stdout = false;
  std::string path;    // the file (to_stdout: empty)
  std::string format;  // obj, ply, off or stl
  std::string error;   // why the mesh could not be written there; "" if fine
  // As reports show it: the path, or "-".
  std::string Name() const { return to_stdout ? "-" : path; }
};
// How a subcommand names its outputs when the user does not.
struct OutputDefaults {
  std::string suffix = "tri";            // beside the input: NAME.SUFFIX.FORMAT
  std::string file_format = "obj";       // of a file named from the input
  std::string stdout_format = "obj";     // of stdout
  std::string format_flag = "--format";  // named in errors
};
// Resolves, and checks before any work, where the mesh of `input` goes.
// `output` is the -o value: "" beside the input (NAME.SUFFIX.FORMAT; stdout
// for a stream input), "-" stdout, a directory (DIR/NAME.FORMAT) when
// `into_directory` or when it is one or ends with '/', else the file.
// `format` is the format flag: "" means from the extension (the defaults'
// otherwise); with a file of no or an unknown extension it decides, and
// contradicting the extension is an error. The check: the format is known,
// the path is not a directory and not the input itself, with the reason
// in `error` when not.
OutputTarget ResolveOutput(const std::string& input, const std::string& output,
                           const std::string& format, bool into_directory,
                           const OutputDefaults& defaults = {});
// Whether two paths name one file: the same file when both exist (links,
// "./x", absolute or relative), else the same normalized path. "-" names
// no file.
bool SameFile(const std::string& a, const std::string& b);
// Whether `path` ends in a mesh format's extension (.obj, .ply, .off).
bool NamesMeshFile(const std::string& path);
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

}  // namespace dot::client

#endif  // DOT_CLIENT_CLI_OUTPUT_H_
