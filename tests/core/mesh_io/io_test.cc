// SPDX-License-Identifier: AGPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "dot/dot.h"
#include "fixtures/temp_files.h"

namespace dot {
namespace {

std::string TempPath(const std::string& name) {
  return testing::TempPath("io_test", name);
}

TEST(IoTest, PlainTextWithAndWithoutNormals) {
  std::istringstream in("# a comment\n0 0 0\n# another\n1 0 0\n1 1 0.5\n\n");
  PolygonData p;
  ASSERT_TRUE(ReadPolygonText(in, &p).ok());
  ASSERT_EQ(p.vertices.size(), 3u);
  EXPECT_EQ(p.vertices[2], (Vec3{1, 1, 0.5}));
  EXPECT_TRUE(p.normals.empty());
  EXPECT_TRUE(p.loop_sizes.empty());

  std::istringstream with("0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 1 1\n");
  ASSERT_TRUE(ReadPolygonText(with, &p).ok());
  ASSERT_EQ(p.normals.size(), 3u);
  EXPECT_EQ(p.normals[2], (Vec3{0, 1, 1}));
}

TEST(IoTest, PlainTextErrorsNameTheLine) {
  PolygonData p;
  std::istringstream bad("0 0 0\n1 0\n");
  Status s = ReadPolygonText(bad, &p);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("line 2: expected 3"), std::string::npos)
      << s.message;
  std::istringstream word("0 0 0\n1 0 zero\n");
  s = ReadPolygonText(word, &p);
  EXPECT_NE(s.message.find("line 2: 'zero' is not a number"), std::string::npos)
      << s.message;
}

TEST(IoTest, ObjPolylineOrderNegativeIndicesAndClosingIndex) {
  std::istringstream in("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nl 1 3 -3 4 1\n");
  PolygonData p;
  ASSERT_TRUE(ReadPolygonObj(in, &p).ok());
  ASSERT_EQ(p.vertices.size(), 4u);
  EXPECT_EQ(p.vertices[1], (Vec3{1, 1, 0}));
  EXPECT_EQ(p.vertices[2], (Vec3{1, 0, 0}));
  std::istringstream bad("v 0 0 0\nl 1 7\n");
  const Status s = ReadPolygonObj(bad, &p);
  EXPECT_NE(s.message.find("index '7' is out of range"), std::string::npos);
}

TEST(IoTest, LoopRepeatingItsFirstPointHasTheRepeatDropped) {
  std::vector<std::string> notes;
  PolygonData p;
  std::istringstream text(
      "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n"
      "0 0 0 0 0 1\n");
  ASSERT_TRUE(ReadPolygonText(text, &p, &notes).ok());
  EXPECT_EQ(p.vertices.size(), 3u);
  EXPECT_EQ(p.normals.size(), 3u);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("repeat of the first"), std::string::npos)
      << notes[0];
  // Idempotent: several repeats go, an open loop is left alone.
  std::istringstream twice("0 0 0\n1 0 0\n1 1 0\n0 0 0\n0 0 0\n");
  ASSERT_TRUE(ReadPolygonText(twice, &p).ok());
  EXPECT_EQ(p.vertices.size(), 3u);
  notes.clear();
  std::istringstream open("0 0 0\n1 0 0\n1 1 0\n");
  ASSERT_TRUE(ReadPolygonText(open, &p, &notes).ok());
  EXPECT_EQ(p.vertices.size(), 3u);
  EXPECT_TRUE(notes.empty());
  // OBJ: a closing vertex with the first one's coordinates but its own index.
  std::istringstream obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nl 1 2 3 4\n");
  ASSERT_TRUE(ReadPolygonObj(obj, &p, &notes).ok());
  EXPECT_EQ(p.vertices.size(), 3u);
  EXPECT_EQ(notes.size(), 1u);
}

TEST(IoTest, ObjEdgePerLineIsChainedIntoTheLoop) {
  // As Blender writes a loop: one "l a b" per edge, in any order and
  // direction; the loop starts with the first edge, in its direction.
  std::istringstream in(
      "o Loop\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n"
      "l 2 3\nl 4 3\nl 1 2\nl 4 5\nl 5 1\n");
  PolygonData p;
  const Status s = ReadPolygonObj(in, &p);
  ASSERT_TRUE(s.ok()) << s.message;
  ASSERT_EQ(p.vertices.size(), 5u);
  const std::vector<Vec3> want{
      {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}, {0, 0, 0}};
  EXPECT_EQ(p.vertices, want);

  const auto refused = [](const std::string& text) {
    std::istringstream bad(text);
    PolygonData q;
    return ReadPolygonObj(bad, &q).message;
  };
  const std::string four = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  EXPECT_NE(refused(four + "l 1 2\nl 2 3\nl 3 4\n")
                .find("do not close into a loop: vertex 1 ends an open chain"),
            std::string::npos);
  EXPECT_NE(refused(four + "l 1 2\nl 2 3\nl 3 1\nl 2 4\nl 4 1\n")
                .find("branch at vertex 1 (3 edges)"),
            std::string::npos);
}

TEST(IoTest, SeveralLoopsAsBlocksOrObjLoops) {
  // Text: blank lines separate loops; each loop's closing repeat is dropped.
  std::istringstream text(
      "0 0 0\n1 0 0\n1 1 0\n0 0 0\n\n\n# island\n"
      "0.2 0.2 0.1\n0.3 0.2 0.1\n0.3 0.3 0.1\n0.2 0.3 0.1\n");
  PolygonData p;
  std::vector<std::string> notes;
  ASSERT_TRUE(ReadPolygonText(text, &p, &notes).ok());
  EXPECT_EQ(p.loop_sizes, (std::vector<int32_t>{3, 4}));
  EXPECT_EQ(p.vertices.size(), 7u);
  EXPECT_EQ(p.vertices[3], (Vec3{0.2, 0.2, 0.1}));
  ASSERT_EQ(notes.size(), 2u);  // the closing repeat, and the loop count
  EXPECT_NE(notes[1].find("read 2 loops"), std::string::npos) << notes[1];
  std::istringstream short_block("0 0 0\n1 0 0\n\n0 1 0\n1 1 0\n2 2 0\n");
  const Status s = ReadPolygonText(short_block, &p);
  EXPECT_NE(s.message.find("line 3: a blank line ends loop 1 after 2 "
                           "vertices; a loop needs at least 3"),
            std::string::npos)
      << s.message;

  // A last loop too short, with no blank line after it to say so.
  std::istringstream short_last("0 0 0\n1 0 0\n1 1 0\n\n0 1 0\n");
  EXPECT_NE(ReadPolygonText(short_last, &p)
                .message.find("the last loop (loop 2) has 1 vertex"),
            std::string::npos);

  // OBJ: 'l' lines closing into two loops, in the order they appear.
  const std::string six =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n";
  std::istringstream obj(six + "l 1 2\nl 2 4\nl 4 1\nl 3 5\nl 5 6\nl 6 3\n");
  ASSERT_TRUE(ReadPolygonObj(obj, &p).ok());
  EXPECT_EQ(p.loop_sizes, (std::vector<int32_t>{3, 3}));
  EXPECT_EQ(p.vertices[3], (Vec3{1, 1, 0}));
  // Closed polylines, one per loop, as curve tools write them.
  std::istringstream closed(six + "l 1 2 4 1\nl 3 5 6 3\n");
  ASSERT_TRUE(ReadPolygonObj(closed, &p).ok());
  EXPECT_EQ(p.loop_sizes, (std::vector<int32_t>{3, 3}));

  // The writer separates loops with a blank line: a round trip.
  std::ostringstream out;
  ASSERT_TRUE(WritePolygonText(out, p).ok());
  std::istringstream back(out.str());
  PolygonData q;
  ASSERT_TRUE(ReadPolygonText(back, &q).ok());
  EXPECT_EQ(q.vertices, p.vertices);
  EXPECT_EQ(q.loop_sizes, p.loop_sizes);
}

TEST(IoTest, MeshRoundTripsThroughEveryFormat) {
  Problem prob{MakeCurve(Curve::kMonkey, 60), {}, {}, {}, {}};
  const Result r = Triangulate(prob);
  ASSERT_TRUE(r.status.ok());
  const MeshData mesh{r.vertices, r.triangles};
  for (const char* ext : {"obj", "off"}) {
    const std::string path = TempPath(std::string("mesh.") + ext);
    ASSERT_TRUE(WriteMeshFile(path, mesh).ok());
    MeshData back;
    ASSERT_TRUE(ReadMeshFile(path, &back).ok()) << ext;
    EXPECT_EQ(back.triangles, mesh.triangles) << ext;
    ASSERT_EQ(back.vertices.size(), mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      EXPECT_EQ(back.vertices[i], mesh.vertices[i]) << ext;  // %.17g
    }
    std::remove(path.c_str());
  }
  std::ostringstream ply;
  ASSERT_TRUE(WriteMesh(ply, "ply", mesh).ok());
  EXPECT_NE(ply.str().find("element face 58"), std::string::npos);
  EXPECT_EQ(WriteMeshFile(TempPath("mesh.xyz"), mesh).code,
            StatusCode::kInvalidArgument);
}

TEST(IoTest, StlIsWrittenBinaryInFloatsOrAsciiWithEveryDigit) {
  Problem prob;
  prob.vertices = MakeCurve(Curve::kMonkey, 60);
  const Result r = Triangulate(prob);
  ASSERT_TRUE(r.status.ok());
  const MeshData mesh{r.vertices, r.triangles};
  for (const bool ascii : {false, true}) {
    const std::string path = TempPath(ascii ? "ascii.stl" : "binary.stl");
    {
      std::ofstream out(path, std::ios::binary);
      ASSERT_TRUE(WriteMesh(out, "stl", mesh, ascii).ok());
    }
    PolygonSoup back;
    ASSERT_TRUE(ReadPolygonSoupFile(path, &back).ok()) << path;
    ASSERT_EQ(back.faces.size(), mesh.triangles.size()) << path;
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
      ASSERT_EQ(back.faces[f].size(), 3u);
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = mesh.vertices[mesh.triangles[f][k]];
        // STL is single precision: readers (CGAL's too) round even
        // ASCII values to float, so each coordinate is within half a
        // float ulp (2^-24 relative).
        const Vec3& q = back.vertices[back.faces[f][k]];
        for (const auto& [got, sent] :
             {std::pair{q.x, p.x}, std::pair{q.y, p.y}, std::pair{q.z, p.z}}) {
          EXPECT_LE(std::abs(got - sent), std::abs(sent) * 0x1p-24)
              << path << " face " << f;
        }
      }
    }
    std::remove(path.c_str());
  }
  // Each facet's normal is its unit normal by the right-hand rule.
  const MeshData one{{{0, 0, 0}, {2, 0, 0}, {0, 3, 0}}, {{0, 1, 2}}};
  std::ostringstream text;
  ASSERT_TRUE(WriteMesh(text, "stl", one, /*ascii=*/true).ok());
  EXPECT_NE(text.str().find("facet normal 0 0 1"), std::string::npos)
      << text.str();
  // ASCII keeps every digit in the file, for readers that take doubles.
  const MeshData fine{{{0.1, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}};
  std::ostringstream digits;
  ASSERT_TRUE(WriteMesh(digits, "stl", fine, /*ascii=*/true).ok());
  EXPECT_NE(digits.str().find("vertex 0.10000000000000001 0 0"),
            std::string::npos)
      << digits.str();
}

TEST(IoTest, PolygonFileRoundTrip) {
  PolygonData p{MakeCurve(Curve::kSpiral, 30), {}};
  for (size_t i = 0; i < p.vertices.size(); ++i) p.normals.push_back({0, 0, 1});
  const std::string path = TempPath("poly.xyz");
  ASSERT_TRUE(WritePolygonText(path, p).ok());
  PolygonData back;
  ASSERT_TRUE(ReadPolygonFile(path, &back).ok());
  EXPECT_EQ(back.vertices.size(), p.vertices.size());
  EXPECT_EQ(back.vertices[7], p.vertices[7]);
  EXPECT_EQ(back.normals.size(), p.normals.size());
  std::remove(path.c_str());
  EXPECT_NE(
      ReadPolygonFile("/nonexistent/x.xyz", &back).message.find("cannot open"),
      std::string::npos);
}

}  // namespace
}  // namespace dot
