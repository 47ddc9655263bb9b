// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl surface and generate network end to end: over a real server and
// locally (the same bytes), stdin and stdout, --cycles, the JSON report,
// exit codes, errors naming the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "dot/dot.h"
#include "fixtures/dotctl_run.h"
#include "fixtures/service_fixture.h"

namespace dot {
namespace {

using testing::Dotctl;

class SurfaceCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = testing::StartServer(testing::LoopbackConfig());
    dir_ = testing::TempDir("surface-cli");
    flag_ = "--server " + server_.address + " ";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const {
    return (dir_ / name).string();
  }
  static std::string Read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  testing::RunningServer server_;
  std::filesystem::path dir_;
  std::string flag_;
};

TEST_F(SurfaceCliTest, CutMeshNetworkLocalAndRemoteAgree) {
  auto r = Dotctl("generate network " + std::string(DOT_MESH_DIR) +
                  "/homer.off -p 60 --keep-every 2 -o " + Path("net.obj"));
  ASSERT_EQ(r.code, 0) << r.out;
  r = Dotctl("surface --local " + Path("net.obj") + " -o " + Path("local.ply"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("closed"), std::string::npos) << r.out;
  r = Dotctl(flag_ + "surface " + Path("net.obj") + " -o " +
             Path("remote.ply"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(Read(Path("local.ply")), Read(Path("remote.ply")));
  MeshData surface;
  ASSERT_TRUE(ReadMeshFile(Path("remote.ply"), &surface).ok());
  EXPECT_EQ(ShapeOf(surface).euler, 2);
  EXPECT_EQ(CountIntersectingPairs(surface.vertices, surface.triangles), 0);
}

TEST_F(SurfaceCliTest, JsonStagesStdinAndCycles) {
  ASSERT_EQ(Dotctl("generate network cube -s 3 -o " + Path("cube.obj")).code,
            0);
  auto r = Dotctl(flag_ + "surface " + Path("cube.obj") + " -o " +
                  Path("cube.off") + " --stage triangulate --json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"outcome\":\"ok\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"surfaced\":6,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"closed\":true"), std::string::npos) << r.out;
  // stdin to stdout.
  r = testing::RunShell("cat " + Path("cube.obj") + " | " +
                        std::string(DOT_DOTCTL_PATH) +
                        " surface --local - --output-format off -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.rfind("OFF", 0), 0u) << r.out.substr(0, 80);
  // Two faces of the cube given by their corners (OBJ numbering): an open
  // surface, exit 0.
  {
    std::ofstream cycles(Path("cycles.txt"));
    cycles << "# z = 0 and y = 0\n1 2 4 3\n1 5 6 2\n";
  }
  r = Dotctl("surface --local " + Path("cube.obj") + " --cycles " +
             Path("cycles.txt") + " -o " + Path("two.off") + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"surfaced\":2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"closed\":false"), std::string::npos) << r.out;
}

// A circle on the cube's lid: over the server an island of the lid and a
// patch of its own (closed, genus 0), or with --islands hole a hole (exit
// 0: the open surface is what was asked), the same locally.
TEST_F(SurfaceCliTest, LoopOnAFaceIsAnIslandOrAHole) {
  ASSERT_EQ(Dotctl("generate network lid -s 2 -o " + Path("lid.obj")).code, 0);
  auto r = Dotctl(flag_ + "surface " + Path("lid.obj") + " -o " +
                  Path("inset.ply") + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"surfaced\":7,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"closed\":true"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("an island of it"), std::string::npos) << r.out;
  MeshData inset;
  ASSERT_TRUE(ReadMeshFile(Path("inset.ply"), &inset).ok());
  EXPECT_EQ(ShapeOf(inset).euler, 2);
  EXPECT_EQ(CountIntersectingPairs(inset.vertices, inset.triangles), 0);
  for (const std::string& how :
       {flag_ + "surface ", std::string("surface --local ")}) {
    r = Dotctl(how + Path("lid.obj") + " --islands hole -o " +
               Path("hole.ply") + " --json");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("\"surfaced\":6,"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"closed\":false"), std::string::npos) << r.out;
    MeshData hole;
    ASSERT_TRUE(ReadMeshFile(Path("hole.ply"), &hole).ok());
    EXPECT_EQ(ShapeOf(hole).euler, 1);
  }
  r = Dotctl(flag_ + "surface " + Path("lid.obj") + " --islands some -o -");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--islands"), std::string::npos) << r.out;
}

// Two cubes side by side: one box (10 patches) unless --walls, then the
// square between them too, a third patch on each of its 4 curves.
TEST_F(SurfaceCliTest, WallsOnlyWithTheFlag) {
  ASSERT_EQ(Dotctl("generate network partition -s 2 -o " + Path("p.obj")).code,
            0);
  auto r = Dotctl(flag_ + "surface " + Path("p.obj") + " -o " +
                  Path("box.ply") + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"surfaced\":10,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"non_manifold_curves\":0"), std::string::npos);
  r = Dotctl(flag_ + "surface " + Path("p.obj") + " --walls -o " +
             Path("walls.ply") + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"surfaced\":11,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"non_manifold_curves\":4"), std::string::npos);
  EXPECT_NE(r.out.find("a wall (curves"), std::string::npos) << r.out;
}

// A triangle and a square that share an edge, drawn as three strokes whose
// ends miss each other by up to 0.003: with --weld 0.01 they meet at two
// junctions and close (the two faces and the one around both, as a
// network with no open rim does), locally and over the server; without,
// every stroke dangles and nothing is surfaced (exit 2).
TEST_F(SurfaceCliTest, WeldJoinsStrokesThatNearlyMeet) {
  {
    std::ofstream strokes(Path("strokes.obj"));
    strokes << "v 0 0 0\nv 1 0 0\n"  // shared edge
            << "v 1.002 0.001 0\nv 1 1 0\nv 0 1 0\nv 0.001 0.003 0\n"  // square
            << "v 0.003 -0.001 0\nv 0.5 -1 0.2\nv 0.998 -0.002 0\n"  // triangle
            << "l 1 2\nl 3 4 5 6\nl 7 8 9\n";
  }
  auto r = Dotctl("surface --local " + Path("strokes.obj") + " -o " +
                  Path("x.ply") + " --json");
  EXPECT_EQ(r.code, 2) << r.out;
  for (const std::string& where : {std::string("--local "), flag_}) {
    r = Dotctl("surface " + where + Path("strokes.obj") + " --weld 0.01 -o " +
               Path("welded.ply") + " --json");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("\"surfaced\":3,"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"closed\":true"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("within --weld"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"merged_vertices\":4"), std::string::npos) << r.out;
  }
  r = Dotctl("surface --local " + Path("strokes.obj") + " --weld -1 -o " +
             Path("x.ply"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--weld"), std::string::npos) << r.out;
}

TEST_F(SurfaceCliTest, BadInputsAreNamed) {
  {
    std::ofstream bad(Path("bad.obj"));
    bad << "v 0 0 0\nv 1 0 0\nl 1 7\n";
  }
  auto r =
      Dotctl("surface --local " + Path("bad.obj") + " -o " + Path("x.ply"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("line 3"), std::string::npos) << r.out;
  {
    std::ofstream cycles(Path("cycles.txt"));
    cycles << "1 2 x\n";
  }
  ASSERT_EQ(Dotctl("generate network cube -o " + Path("cube.obj")).code, 0);
  r = Dotctl(flag_ + "surface " + Path("cube.obj") + " --cycles " +
             Path("cycles.txt") + " -o " + Path("x.ply") + " --json");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("\"outcome\":\"input_error\""), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("'x'"), std::string::npos) << r.out;
  // A cycle that is not one: the server names it.
  {
    std::ofstream cycles(Path("cycles.txt"));
    cycles << "1 8 4\n";
  }
  r = Dotctl(flag_ + "surface " + Path("cube.obj") + " --cycles " +
             Path("cycles.txt") + " -o " + Path("x.ply"));
  EXPECT_EQ(r.code, 2) << r.out;
  // Numbered from 0, as the service numbers (the file's "1 8").
  EXPECT_NE(r.out.find("no curve joins vertices 0 and 7"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("numbered from 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cycle 0 the cycles file's first listed cycle"),
            std::string::npos)
      << r.out;
  // Curves that cross are named by number, the hint without cycles; an
  // error that numbers nothing gets no hint.
  {
    std::ofstream cross(Path("cross.obj"));
    cross << "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 3 4\n";
  }
  r = Dotctl(flag_ + "surface " + Path("cross.obj") + " -o " + Path("x.ply"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("of polyline 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("polyline 0 its first)"), std::string::npos) << r.out;
  {
    std::ofstream open(Path("open.obj"));
    open << "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\n";
  }
  r = Dotctl(flag_ + "surface " + Path("open.obj") + " -o " + Path("x.ply"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("bounds no patch"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("numbered from 0"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace dot
