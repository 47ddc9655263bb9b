// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-delaunay-helper: runs TetGen for dot-server over stdin/stdout (see
// delaunay_helpers.h). Caps its own address space first, so that a runaway
// tetrahedralization fails this process, not the server.
#include <sys/resource.h>

#include <cstdlib>
#include <cstring>
#include <iostream>

#include "compute/delaunay_helpers.h"

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--memory-limit-bytes") == 0 && i + 1 < argc) {
      const rlim_t limit = std::strtoull(argv[++i], nullptr, 10);
      const rlimit rl{limit, limit};
      if (dot::server::kCanCapAddressSpace && limit > 0 &&
          setrlimit(RLIMIT_AS, &rl) != 0) {
        std::cerr << "dot-delaunay-helper: setrlimit failed\n";
        return 2;
      }
    } else {
      std::cerr << "usage: dot-delaunay-helper [--memory-limit-bytes N]\n"
                   "Started by dot-server; speaks a binary protocol on "
                   "stdin/stdout.\n";
      return 2;
    }
  }
  return dot::server::RunDelaunayHelper(0, 1);
}
