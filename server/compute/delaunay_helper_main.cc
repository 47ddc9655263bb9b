// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-delaunay-helper: runs TetGen for dot-server over stdin/stdout (see
// dot/delaunay_helpers.h). Caps its own address space first, so that a
// runaway tetrahedralization fails this process, not the server.
#include "dot/delaunay_helpers.h"

int main(int argc, char** argv) {
  return dot::DelaunayHelperMain("dot-delaunay-helper", argc, argv);
}
