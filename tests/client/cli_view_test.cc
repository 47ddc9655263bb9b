// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl view and fill-holes --report as files: where pages go, and that
// a page never replaces a mesh, under any name. (The pages themselves:
// view_page_test.cc and, in Chromium, viewer_test.cjs.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "fixtures/dotctl_run.h"
#include "view_page.h"

namespace dot {
namespace {

using testing::CliRun;
using testing::Dotctl;
using testing::RunShell;

std::string Head(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  return line;
}

class ViewCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!client::ViewerBuilt()) GTEST_SKIP() << "built without the viewer";
    dir_ = testing::TempDir("cli-view");
    std::filesystem::copy_file(DOT_MESH_DIR "/lion.off", dir_ / "lion.off");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  CliRun In(const std::string& command) const {
    return RunShell("cd " + dir_.string() + " && " + command);
  }
  std::filesystem::path dir_;
};

TEST_F(ViewCliTest, ReadsStdinAndWritesStdout) {
  const CliRun r = In(std::string(DOT_DOTCTL_PATH) +
                      " view - --input-format off < lion.off > stdin.html");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(Head(dir_ / "stdin.html"), "<!DOCTYPE html>");
  // -o DIR/ puts NAME.html in it, made if missing.
  ASSERT_EQ(In(std::string(DOT_DOTCTL_PATH) + " view lion.off -o pages/").code,
            0);
  EXPECT_EQ(Head(dir_ / "pages" / "lion.html"), "<!DOCTYPE html>");
}

// The input named another way (./, absolute, a link) is still the input.
TEST_F(ViewCliTest, NeverOverwritesTheMeshItShows) {
  std::filesystem::create_symlink(dir_ / "lion.off", dir_ / "link.off");
  const std::string dotctl = DOT_DOTCTL_PATH;
  for (const std::string& args :
       {std::string("view lion.off -o ./lion.off"),
        "view lion.off -o " + (dir_ / "lion.off").string(),
        std::string("view link.off -o lion.off")}) {
    const CliRun r = In(dotctl + " " + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_NE(r.out.find("would overwrite"), std::string::npos) << r.out;
    EXPECT_EQ(Head(dir_ / "lion.off"), "OFF") << args;
  }
}

TEST_F(ViewCliTest, ReportNeverReplacesAMeshOrSharesStdout) {
  const std::string fill =
      std::string(DOT_DOTCTL_PATH) + " fill-holes lion.off --local ";
  struct Case {
    std::string flags, why;
  };
  for (const Case& c :
       {Case{"-o f.ply --report ./lion.off", "would overwrite the input"},
        Case{"-o f.ply --report ./f.ply", "would overwrite the filled mesh"},
        Case{"-o - --report -", "would both write stdout"},
        Case{"-o f.ply --report - --json", "would both write stdout"}}) {
    // Whatever reached stdout (the --json envelope) goes to a file.
    const CliRun r =
        In(fill + c.flags +
           " 2>err.txt >out.txt; s=$?; cat err.txt out.txt; exit $s");
    EXPECT_EQ(r.code, 2) << c.flags << ": " << r.out;
    EXPECT_NE(r.out.find(c.why), std::string::npos) << r.out;
    EXPECT_EQ(Head(dir_ / "lion.off"), "OFF");
    EXPECT_FALSE(std::filesystem::exists(dir_ / "f.ply")) << c.flags;
  }
  // A new directory for one mesh's page is made.
  const CliRun ok = In(fill + "-o f.ply --report new/dir/ -q");
  ASSERT_EQ(ok.code, 0) << ok.out;
  EXPECT_EQ(Head(dir_ / "new" / "dir" / "lion.html"), "<!DOCTYPE html>");
}

// Two inputs of one name would write one page (and one mesh) in the
// output directories: refused before any work.
TEST_F(ViewCliTest, InputsOfOneNameAreRefusedForOneDirectory) {
  std::filesystem::create_directories(dir_ / "a");
  std::filesystem::copy_file(dir_ / "lion.off", dir_ / "a" / "lion.off");
  const CliRun r = In(std::string(DOT_DOTCTL_PATH) +
                      " fill-holes lion.off a/lion.off --local --report "
                      "pages/ -o out/");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("would be written to one file"), std::string::npos)
      << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "lion.ply"));
}

}  // namespace
}  // namespace dot
