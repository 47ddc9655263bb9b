// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl --local: the core in this process, with TetGen in helper processes
// (dotctl itself, in its helper mode) as dot-server runs it.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "dot/triangulate.h"
#include "fixtures/dotctl_run.h"

namespace dot {
namespace {

using testing::CliRun;
using testing::Dotctl;

std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

// TetGen 1.5.0 fails an assertion in tetgenmesh::locate on this polygon
// (found by triangulate_fuzz: a long run of nearly collinear points). Run
// in-process, TetGen's abort() took dotctl down with it; now the helper
// dies and dotctl reports the input as failed, with its usual exit code.
TEST(CliLocalTest, TetgenAbortFailsTheInputNotDotctl) {
  if (!TetgenAvailable()) GTEST_SKIP() << "built without TetGen";
  const std::string input = DOT_TEST_DATA_DIR "/tetgen_aborts.xyz";
  const CliRun r = Dotctl("triangulate --local --delaunay tetgen --json " +
                          input + " --format obj -o -");
  EXPECT_EQ(r.code, 1) << r.out;  // a request failed (not a signal: -1)
  EXPECT_NE(
      r.out.find(
          "INTERNAL: the helper process running the Delaunay step crashed"),
      std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"outcome\":\"call_failed\""), std::string::npos)
      << r.out;
  // CGAL's Delaunay of the same polygon is computed: it answers (this
  // polygon has an edge on no Delaunay triangle).
  const CliRun cgal = Dotctl("triangulate --local --delaunay cgal " + input +
                             " --format obj -o /dev/null");
  EXPECT_EQ(cgal.code, 4) << cgal.out;
  EXPECT_NE(cgal.out.find("no triangulation"), std::string::npos) << cgal.out;
}

// With TetGen in a helper, a polygon gets the same mesh as with CGAL, and
// several inputs in one run reuse the helper.
TEST(CliLocalTest, TetgenHelperAgreesWithCgal) {
  if (!TetgenAvailable()) GTEST_SKIP() << "built without TetGen";
  const auto dir = testing::TempDir("cli-local");
  const std::string saddle = (dir / "saddle.xyz").string();
  const std::string spiral = (dir / "spiral.xyz").string();
  ASSERT_EQ(Dotctl("generate curve monkey -n 60 -o " + saddle).code, 0);
  ASSERT_EQ(Dotctl("generate curve spiral -n 80 -o " + spiral).code, 0);
  for (const char* backend : {"tetgen", "cgal"}) {
    const std::string out = (dir / backend).string();
    const CliRun r = Dotctl(
        std::string("triangulate --local --space delaunay --delaunay ") +
        backend + " " + saddle + " " + spiral + " --format obj -o " + out);
    EXPECT_EQ(r.code, 0) << backend << ": " << r.out;
    if (std::string(backend) == "tetgen") {
      EXPECT_NE(r.out.find("(tetgen)"), std::string::npos) << r.out;
    }
  }
  for (const char* name : {"saddle.obj", "spiral.obj"}) {
    const std::string tetgen = ReadFile(dir / "tetgen" / name);
    EXPECT_FALSE(tetgen.empty()) << name;
    EXPECT_EQ(tetgen, ReadFile(dir / "cgal" / name)) << name;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dot
