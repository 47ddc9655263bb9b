// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl triangulate with several loops in one file (blank-line blocks, OBJ
// 'l' loops): one surface joining them, through a real server and locally
// alike, the reversal reported, and the mesh checked as an annulus.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "dot/dot.h"
#include "fixtures/dotctl_run.h"
#include "fixtures/service_fixture.h"

namespace dot {
namespace {

using testing::Dotctl;

TEST(CliLoopsTest, TwoLoopsInOneFileBecomeOneSurfaceRemoteAndLocal) {
  const testing::RunningServer server =
      testing::StartServer(testing::LoopbackConfig());
  const auto dir = testing::TempDir("cli-loops");
  const std::string xyz = (dir / "tube.xyz").string();
  {
    std::ofstream f(xyz);
    f.precision(17);
    for (int l = 0; l < 2; ++l) {
      for (int i = 0; i < 32; ++i) {
        // Both rims counter-clockwise: the solver must reverse one.
        const double a = 2 * kPi * i / 32, r = l ? 0.7 : 1.0;
        f << r * std::cos(a) << " " << r * std::sin(a) << " "
          << 0.8 * l + 0.05 * std::sin(3 * a) << "\n";
      }
      f << "\n";
    }
  }
  std::string meshes[2];
  for (int local = 0; local < 2; ++local) {
    const std::string out =
        (dir / (local ? "local.obj" : "remote.obj")).string();
    const std::string how =
        local ? "--local " : "--server " + server.address + " ";
    const testing::CliRun r = Dotctl("triangulate " + how + xyz + " -o " + out);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("64 triangles joining 2 loops (loop 1 reversed)"),
              std::string::npos)
        << r.out;
    MeshData mesh;
    ASSERT_TRUE(ReadMeshFile(out, &mesh).ok());
    std::vector<int32_t> rim0(32), rim1(32);
    for (int i = 0; i < 32; ++i) {
      rim0[i] = i;
      rim1[i] = 32 + (32 - i) % 32;  // reversed, from its first vertex
    }
    const MeshReport report =
        ValidateSurface(mesh.vertices, {rim0, rim1}, mesh.triangles);
    EXPECT_TRUE(report.valid()) << report.first_problem;
    std::ifstream in(out);
    meshes[local] = {std::istreambuf_iterator<char>(in), {}};
  }
  EXPECT_EQ(meshes[0], meshes[1]);  // the server answers as --local does

  // Kept as given, the rims have no surface: exit code 4, and the JSON
  // summary carries the loop fields.
  const testing::CliRun kept = Dotctl(
      "triangulate --local "
      "--keep-loop-directions --json " +
      xyz + " --format obj -o /dev/null");
  EXPECT_EQ(kept.code, 4) << kept.out;
  EXPECT_NE(kept.out.find("loop 1 running its given way; one does with it "
                          "reversed"),
            std::string::npos)
      << kept.out;
  EXPECT_NE(kept.out.find("\"loop_sizes\":[32,32]"), std::string::npos)
      << kept.out;
  std::filesystem::remove_all(dir);
}

TEST(CliLoopsTest, GeneratedLoopPairsTriangulate) {
  const auto dir = testing::TempDir("cli-loops-generate");
  for (const char* kind : {"tube", "island"}) {
    const std::string xyz = (dir / (std::string(kind) + ".xyz")).string();
    ASSERT_EQ(
        Dotctl(std::string("generate loops ") + kind + " -n 40 -o " + xyz).code,
        0);
    PolygonData read;
    std::vector<std::string> notes;
    ASSERT_TRUE(ReadPolygonFile(xyz, &read, &notes).ok());
    EXPECT_EQ(read.loop_sizes, (std::vector<int32_t>{40, 40}));
    EXPECT_EQ(read.vertices,
              MakeLoopPair(*LoopPairFromName(kind), 40).vertices);
    const testing::CliRun r =
        Dotctl("triangulate --local --keep-loop-directions " + xyz +
               " --format obj -o /dev/null");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("80 triangles joining 2 loops,"), std::string::npos)
        << r.out;
  }
  EXPECT_NE(Dotctl("generate loops torus -o /dev/null").code, 0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dot
