// SPDX-License-Identifier: AGPL-3.0-or-later
// TetGen in a helper process for the fuzz targets, as dot-server runs it:
// the core's DelaunayHelperPool with the dot-delaunay-helper of this build
// (DOT_DELAUNAY_HELPER_PATH). TetGen 1.5.0 (Debian's libtet) aborts on some
// degenerate point sets (assertions in tetgenmesh::insphere_s and locate);
// the helper dies, the call fails with INTERNAL naming the crash, and the
// fuzzers go on testing our code around TetGen rather than TetGen itself.
#ifndef DOT_TESTS_FUZZ_TETGEN_CHILD_H_
#define DOT_TESTS_FUZZ_TETGEN_CHILD_H_

#include <chrono>
#include <vector>

#include "dot/delaunay_helpers.h"

#ifndef DOT_DELAUNAY_HELPER_PATH  // a build without TetGen never calls it
#define DOT_DELAUNAY_HELPER_PATH "dot-delaunay-helper"
#endif

namespace dot::fuzz {

inline Status TetgenInChild(const std::vector<Vec3>& points,
                            Tetrahedralization* out) {
  // One helper for the fuzzer's life (it outlives every input; libFuzzer
  // exits without unwinding, so it is never destroyed).
  static DelaunayHelperPool* const helpers = [] {
    DelaunayHelperOptions options;
    options.count = 1;
    options.executable = DOT_DELAUNAY_HELPER_PATH;
    options.memory_limit_bytes = 0;  // ASan's shadow memory: no RLIMIT_AS
    return new DelaunayHelperPool(options);
  }();
  return helpers->Tetrahedralize(
      points, out, nullptr,
      std::chrono::steady_clock::now() + std::chrono::seconds(30));
}

}  // namespace dot::fuzz

#endif  // DOT_TESTS_FUZZ_TETGEN_CHILD_H_
