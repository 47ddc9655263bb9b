// SPDX-License-Identifier: AGPL-3.0-or-later
// The common case of OFF, read fast: a plain ASCII "OFF" file of x y z
// vertex lines and "n i1 .. in" face lines (comments and blank lines
// anywhere). Scans come this way, and CGAL's scanner (an istream per
// number) took a quarter of a 1.2 M-face fill reading them. Anything else
// (COFF, NOFF, homogeneous or coloured lines, BINARY, a malformed or
// non-finite item) is left to the careful reader, which names the problem
// by line: this one never decides an error.
#ifndef DOT_CORE_MESH_IO_OFF_FAST_H_
#define DOT_CORE_MESH_IO_OFF_FAST_H_

#include <string>

#include "dot/mesh.h"

namespace dot {

// True when the whole file was read into `out`; false, with `out` cleared,
// when it is not a file this path takes.
bool ReadPlainOffFast(const std::string& path, PolygonSoup* out);

}  // namespace dot

#endif  // DOT_CORE_MESH_IO_OFF_FAST_H_
