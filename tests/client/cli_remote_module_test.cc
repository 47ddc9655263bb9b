// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl's two halves: commands that call no server never load gRPC; the
// remote ones load the dotctl-remote module, and say so clearly when it is
// missing or broken.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "fixtures/dotctl_run.h"

namespace dot {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::Dotctl;
using testing::RunShell;

// Sanitizer builds link the remote half into dotctl (client/CMakeLists.txt).
#if defined(__SANITIZE_ADDRESS__)
#define SKIP_WHERE_LINKED_IN() \
  GTEST_SKIP() << "sanitizer build: dotctl has its remote half linked in"
#else
#define SKIP_WHERE_LINKED_IN() (void)0
#endif

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The dynamic linker's own account of what it loads (LD_DEBUG=libs).
CliRun WithLoaderTrace(const std::string& dotctl, const std::string& args) {
  return RunShell("LD_DEBUG=libs " + dotctl + " " + args);
}

TEST(CliRemoteModuleTest, LocalCommandsNeverLoadGrpc) {
  SKIP_WHERE_LINKED_IN();
  const fs::path dir = testing::TempDir("remote-module-local");
  const std::string curve = (dir / "monkey.xyz").string();
  const std::string cube = (dir / "cube.obj").string();
  for (const std::string& args :
       {std::string("--version"), "generate curve monkey -n 80 -o " + curve,
        "triangulate --local " + curve + " -o " + (dir / "m.ply").string(),
        "generate network cube -o " + cube,
        "surface --local " + cube + " -o " + (dir / "cube.ply").string(),
        "fill-holes --local " + (dir / "cube.ply").string() + " -o " +
            (dir / "same.ply").string(),
        "view " + (dir / "m.ply").string() + " -o " +
            (dir / "m.html").string()}) {
    const CliRun r = WithLoaderTrace(DOT_DOTCTL_PATH, args);
    EXPECT_EQ(r.code, 0) << args << ": " << r.out;
    // The trace works (protobuf is loaded) and names no gRPC library.
    EXPECT_TRUE(Has(r.out, "libprotobuf")) << args << ": " << r.out;
    EXPECT_FALSE(Has(r.out, "libgrpc")) << args;
    EXPECT_FALSE(Has(r.out, "dotctl-remote.so")) << args;
  }
  fs::remove_all(dir);
}

TEST(CliRemoteModuleTest, RemoteCommandsLoadTheModule) {
  SKIP_WHERE_LINKED_IN();
  // Nothing listens on port 1: the module loads, the call is unreachable.
  const CliRun r = WithLoaderTrace(
      DOT_DOTCTL_PATH, "--server 127.0.0.1:1 health --health-timeout 2");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_TRUE(Has(r.out, "dotctl-remote.so")) << r.out;
  EXPECT_TRUE(Has(r.out, "libgrpc")) << r.out;
  EXPECT_TRUE(Has(r.out, "UNREACHABLE")) << r.out;
}

// dotctl alone (copied without its module): the remote commands fail with
// a usage error that names the file looked for; --local still works.
TEST(CliRemoteModuleTest, WithoutItsModuleDotctlSaysWhatIsMissing) {
  SKIP_WHERE_LINKED_IN();
  const fs::path dir = fs::canonical(testing::TempDir("remote-module-alone"));
  const fs::path alone = dir / "dotctl";
  std::error_code ec;
  fs::create_hard_link(DOT_DOTCTL_PATH, alone, ec);  // the same file
  if (ec) fs::copy_file(DOT_DOTCTL_PATH, alone);     // another file system
  const std::string dotctl = alone.string();
  const CliRun missing =
      RunShell(dotctl + " --server 127.0.0.1:1 health --json");
  EXPECT_EQ(missing.code, 2) << missing.out;
  EXPECT_TRUE(Has(missing.out, "\"outcome\":\"connection_error\""))
      << missing.out;
  EXPECT_TRUE(
      Has(missing.out, "cannot find dotctl-remote.so in " + dir.string()))
      << missing.out;
  const std::string curve = (dir / "monkey.xyz").string();
  ASSERT_EQ(RunShell(dotctl + " generate curve monkey -n 80 -o " + curve).code,
            0);
  const CliRun local = RunShell(dotctl + " triangulate --local " + curve +
                                " -o " + (dir / "m.ply").string());
  EXPECT_EQ(local.code, 0) << local.out;
  // A file of that name that is no module is refused with the loader's
  // reason, not a crash.
  std::ofstream(dir / "dotctl-remote.so") << "not a shared object\n";
  const CliRun broken = RunShell(dotctl + " --server 127.0.0.1:1 info");
  EXPECT_EQ(broken.code, 2) << broken.out;
  EXPECT_TRUE(
      Has(broken.out, "cannot load " + (dir / "dotctl-remote.so").string()))
      << broken.out;
  // A module of another build (its entry refuses this dotctl's key).
  fs::copy_file(DOT_FAKE_REMOTE_MODULE, dir / "dotctl-remote.so",
                fs::copy_options::overwrite_existing);
  const CliRun other = RunShell(dotctl + " --server 127.0.0.1:1 info");
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_TRUE(Has(other.out, "is not the remote half of this dotctl"))
      << other.out;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dot
