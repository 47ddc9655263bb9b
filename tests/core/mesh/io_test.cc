// SPDX-License-Identifier: AGPL-3.0-or-later
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dot/dot.h"

namespace dot {
namespace {

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("dot_io_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

TEST(IoTest, PlainTextWithAndWithoutNormals) {
  std::istringstream in("# a comment\n0 0 0\n\n1 0 0\n1 1 0.5\n");
  PolygonData p;
  ASSERT_TRUE(ReadPolygonText(in, &p).ok());
  ASSERT_EQ(p.vertices.size(), 3u);
  EXPECT_EQ(p.vertices[2], (Vec3{1, 1, 0.5}));
  EXPECT_TRUE(p.normals.empty());

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

TEST(IoTest, MeshRoundTripsThroughEveryFormat) {
  Problem prob{MakeCurve(Curve::kMonkey, 60), {}, {}};
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
  EXPECT_EQ(WriteMeshFile(TempPath("mesh.stl"), mesh).code,
            StatusCode::kInvalidArgument);
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
