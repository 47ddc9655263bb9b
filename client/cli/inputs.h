// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl's polygon inputs: files, directories of them, and streams.
#ifndef DOT_CLIENT_CLI_INPUTS_H_
#define DOT_CLIENT_CLI_INPUTS_H_

#include <string>
#include <vector>

#include "dot/dot.h"

namespace dot::client {

// Files named, or found in a directory (those ending in one of
// `extensions`, sorted; by default polygon files: .xyz, .txt, .obj); "-"
// (stdin) and names that do not exist are passed through for the reader to
// report. Error: no files at all.
std::vector<std::string> ExpandInputs(
    const std::vector<std::string>& args, std::string* error,
    const std::vector<std::string>& extensions = {".xyz", ".txt", ".obj"});
// `files` with each path once, at its first mention (the same path named
// twice, or a file named and also found in a directory named: compared as
// absolute paths with `.` and `..` resolved, links not followed; streams by
// name). The later mentions go to `dropped`. For the commands whose inputs
// name their answers (batch keys its stream by input) and their outputs.
std::vector<std::string> EachOnce(const std::vector<std::string>& files,
                                  std::vector<std::string>* dropped);
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

// Reads one mesh (polygons and attribute channels): a file by its
// extension, or "-" and other streams in `format` (off, obj, ply, stl; an
// error without it) through a temporary file, since CGAL's readers detect
// binary PLY and STL from a file. Errors name `input`, never the copy.
Status ReadMeshInput(const std::string& input, const std::string& format,
                     PolygonSoup* soup, std::vector<std::string>* notes);

}  // namespace dot::client

#endif  // DOT_CLIENT_CLI_INPUTS_H_
