// SPDX-License-Identifier: AGPL-3.0-or-later
// OBJ and PLY with their attributes: read into channels, written back, and
// read again to the same values; bad files named by line or item.
#include "mesh_io/mesh_formats.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dot/dot.h"
#include "fixtures/temp_files.h"

namespace dot {
namespace {

std::string TempPath(const std::string& name) {
  return testing::TempPath("formats_test", name);
}

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

const AttributeChannel* Channel(const PolygonSoup& s, const std::string& n) {
  for (const AttributeChannel& ch : s.attributes) {
    if (ch.name == n) return &ch;
  }
  return nullptr;
}

// Value of channel `name` at corner c of vertex v, whatever its domain.
std::vector<float> At(const PolygonSoup& s, const std::string& name, size_t c) {
  const AttributeChannel* ch = Channel(s, name);
  const int32_t v = s.faces.indices()[c];
  const float* e = ch->entry(ch->per_corner() ? ch->indices[c] : v);
  return {e, e + ch->dims};
}

// A quad and a triangle with colours per vertex, UVs and normals per corner
// (vertex 1 is on a UV seam: its two corners name different vt).
const char* kObj =
    "# test\nmtllib x.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\n"
    "v 0 1 0 0.5 0.5 0.5\nv 2 0 0 1 1 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.25 0.75\n"
    "vn 0 0 1\nusemtl m\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf 2/5/1 5/1/1 3/3/1\n";

TEST(MeshFormatsTest, ObjAttributesAreReadPerVertexAndPerCorner) {
  const std::string path = Write("a.obj", kObj);
  PolygonSoup s;
  std::vector<std::string> notes;
  ASSERT_TRUE(ReadPolygonSoupFile(path, &s, &notes).ok());
  EXPECT_EQ(s.vertices.size(), 5u);
  EXPECT_EQ(s.faces.size(), 2u);
  EXPECT_EQ(s.faces[0].size(), 4u);
  ASSERT_NE(Channel(s, "color"), nullptr);
  EXPECT_FALSE(Channel(s, "color")->per_corner());
  EXPECT_EQ(At(s, "color", 1), (std::vector<float>{0, 1, 0}));
  EXPECT_TRUE(Channel(s, "uv")->per_corner());
  EXPECT_EQ(At(s, "uv", 1), (std::vector<float>{1, 0}));
  EXPECT_EQ(At(s, "uv", 4), (std::vector<float>{0.25f, 0.75f}));  // the seam
  EXPECT_EQ(At(s, "normal", 6), (std::vector<float>{0, 0, 1}));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("materials"), std::string::npos);
  std::remove(path.c_str());
}

TEST(MeshFormatsTest, EveryChannelRoundTripsThroughObjAndPly) {
  const std::string path = Write("b.obj", kObj);
  PolygonSoup s;
  ASSERT_TRUE(ReadPolygonSoupFile(path, &s).ok());
  for (const char* format : {"obj", "ply", "ply-ascii"}) {
    const bool ascii = std::string(format) == "ply-ascii";
    const std::string ext = ascii ? "ply" : format;
    const std::string out = TempPath(std::string("round.") + ext);
    std::vector<std::string> notes;
    ASSERT_TRUE(WriteSoupFile(out, s, ascii, &notes).ok()) << format;
    PolygonSoup back;
    ASSERT_TRUE(ReadPolygonSoupFile(out, &back).ok()) << format;
    ASSERT_EQ(back.faces.size(), s.faces.size()) << format;
    ASSERT_EQ(back.faces.corners(), s.faces.corners()) << format;
    for (size_t c = 0; c < s.faces.corners(); ++c) {
      const int32_t v = s.faces.indices()[c], w = back.faces.indices()[c];
      EXPECT_EQ(back.vertices[w], s.vertices[v]) << format << " corner " << c;
      for (const char* ch : {"uv", "normal"}) {
        EXPECT_EQ(At(back, ch, c), At(s, ch, c)) << format << " " << ch;
      }
      // PLY stores colours as bytes: within half a step.
      const auto a = At(back, "color", c), b = At(s, "color", c);
      for (int d = 0; d < 3; ++d)
        EXPECT_NEAR(a[d], b[d], 0.5 / 255 + 1e-6) << format;
    }
    if (ext == "ply") {
      // PLY holds one value per vertex: the seam vertex is written twice.
      EXPECT_EQ(back.vertices.size(), 6u);
      // ... and colours are bytes: 0.5 (vertex 3, three channels) rounds.
      ASSERT_EQ(notes.size(), 2u);
      EXPECT_NE(notes[0].find("1 vertices written twice"), std::string::npos);
      EXPECT_NE(notes[1].find("3 colour values written to the nearest"),
                std::string::npos)
          << notes[1];
    } else {
      EXPECT_EQ(back.vertices.size(), 5u);
      EXPECT_TRUE(notes.empty());
    }
    std::remove(out.c_str());
  }
  std::vector<std::string> notes;
  std::ostringstream off;
  ASSERT_TRUE(WriteSoup(off, "off", s, false, &notes).ok());
  EXPECT_EQ(notes.size(), 3u);  // color, uv and normal have no place in OFF
  EXPECT_NE(off.str().find("\n4 0 1 2 3\n"), std::string::npos);  // the quad
  std::remove(path.c_str());
}

TEST(MeshFormatsTest, PlyPropertiesBecomeChannels) {
  const std::string path = Write(
      "c.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nproperty float nx\n"
      "property float ny\nproperty float nz\nproperty uchar red\n"
      "property uchar green\nproperty uchar blue\nproperty float quality\n"
      "element face 1\nproperty list uchar int vertex_indices\n"
      "property list uchar float texcoord\nproperty uchar red\nend_header\n"
      "0 0 0 0 0 1 255 0 0 0.5\n1 0 0 0 0 1 0 255 0 1.5\n"
      "0 1 0 0 0 1 0 0 255 2.5\n3 0 1 2 6 0 0 1 0 0 1 9\n");
  PolygonSoup s;
  std::vector<std::string> notes;
  ASSERT_TRUE(ReadPolygonSoupFile(path, &s, &notes).ok());
  EXPECT_EQ(At(s, "normal", 2), (std::vector<float>{0, 0, 1}));
  EXPECT_EQ(At(s, "color", 1), (std::vector<float>{0, 1, 0}));
  EXPECT_EQ(At(s, "quality", 2), (std::vector<float>{2.5f}));
  EXPECT_EQ(At(s, "uv", 1), (std::vector<float>{1, 0}));
  ASSERT_EQ(notes.size(), 1u);  // the per-face colour
  EXPECT_NE(notes[0].find("face property 'red'"), std::string::npos);
  std::remove(path.c_str());
}

TEST(MeshFormatsTest, OffColoursObjByteColoursAndLargeFacesAreKept) {
  // COFF: colours per vertex, as bytes.
  const std::string off =
      Write("k.off",
            "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n"
            "0 1 0 0 0 255 255\n3 0 1 2\n");
  PolygonSoup s;
  ASSERT_TRUE(ReadPolygonSoupFile(off, &s).ok());
  ASSERT_NE(Channel(s, "color"), nullptr);
  EXPECT_EQ(At(s, "color", 2), (std::vector<float>{0, 0, 1}));
  // OBJ colours on a 0..255 scale are scaled, with a note.
  const std::string obj = Write(
      "l.obj", "v 0 0 0 255 0 0\nv 1 0 0 0 51 0\nv 0 1 0 0 0 0\nf 1 2 3\n");
  std::vector<std::string> notes;
  ASSERT_TRUE(ReadPolygonSoupFile(obj, &s, &notes).ok());
  EXPECT_EQ(At(s, "color", 1), (std::vector<float>{0, 0.2f, 0}));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("0..255"), std::string::npos);
  // A face of 300 corners stays one face in PLY (16-bit counts).
  PolygonSoup big;
  std::vector<int32_t> ring;
  for (int k = 0; k < 300; ++k) {
    big.vertices.push_back({std::cos(k * 0.02), std::sin(k * 0.02), 0});
    ring.push_back(k);
  }
  big.faces.push_back(ring);
  const std::string ply = TempPath("big.ply");
  ASSERT_TRUE(WriteSoupFile(ply, big).ok());
  PolygonSoup back;
  ASSERT_TRUE(ReadPolygonSoupFile(ply, &back).ok());
  ASSERT_EQ(back.faces.size(), 1u);
  EXPECT_EQ(back.faces[0].size(), 300u);
  for (const std::string& path : {off, obj, ply}) std::remove(path.c_str());
}

// Plain OFF goes through the fast reader: every double exactly as written,
// comments, blank lines, CRLF and polygons as the careful reader takes
// them; what it does not take (COFF, extra numbers, a bad item) goes to
// the careful reader, whose errors name the line.
TEST(MeshFormatsTest, PlainOffIsReadExactlyAndAnythingElseCarefully) {
  std::ostringstream text;
  text.precision(17);
  text << "# a comment\r\nOFF\r\n\n5 2 0 # counts\r\n";
  std::vector<Vec3> points;
  for (int v = 0; v < 5; ++v) {
    points.push_back({0.1 * v + 1e-17 * v, std::sqrt(2.0) * v, -1.0 / (v + 3)});
    text << points.back().x << ' ' << points.back().y << '\t' << points.back().z
         << (v == 2 ? " # middle\r\n" : "\r\n");
  }
  text << "4 0 1 2 3\r\n\n3 0 3 4\n";
  const std::string path = Write("fast.off", text.str());
  PolygonSoup s;
  ASSERT_TRUE(ReadPolygonSoupFile(path, &s).ok());
  EXPECT_EQ(s.vertices, points);
  EXPECT_EQ(s.faces, (FaceList{{0, 1, 2, 3}, {0, 3, 4}}));
  const std::string bad =
      Write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 x\n3 0 1 2\n");
  const Status st = ReadPolygonSoupFile(bad, &s);
  EXPECT_NE(st.message.find("line 5: vertex 2 of 3: 'x' is not a finite"),
            std::string::npos)
      << st.message;
  for (const std::string& p : {path, bad}) std::remove(p.c_str());
}

TEST(MeshFormatsTest, BadFilesAreNamedByLineOrItem) {
  struct Case {
    const char* name;
    const char* text;
    const char* message;
  } cases[] = {
      {"d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
       "line 4: face corner 2 names vertex 4 of 3"},
      {"e.obj", "v 0 0 0\nv 1 0 0\nvt 0 0\nv 0 1 0\nf 1/2 2/1 3/1\n",
       "line 5: face corner 0 names texture coordinate 2 of 1"},
      {"f.obj", "v 0 0\n", "line 1: a vertex needs x y z"},
      {"g.ply",
       "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
       "property float y\nproperty float z\nelement face 1\n"
       "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
       "3 0 1\n",
       "face 0 of 1: list 'vertex_indices' ends before its 3 items"},
      {"h.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
       "property float y\nproperty float z\nelement face 1\n"
       "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
       "0 1 0\n3 0 1 7\n",
       "face 0 has vertex index 7, outside 0..2"},
  };
  for (const Case& c : cases) {
    const std::string path = Write(c.name, c.text);
    PolygonSoup s;
    const Status st = ReadPolygonSoupFile(path, &s);
    EXPECT_EQ(st.code, StatusCode::kInvalidArgument) << c.name;
    EXPECT_NE(st.message.find(c.message), std::string::npos)
        << c.name << ": " << st.message;
    EXPECT_NE(st.message.find(path), std::string::npos) << st.message;
    std::remove(path.c_str());
  }
}

TEST(MeshFormatsTest, BinaryPlyOfEitherByteOrderIsRead) {
  for (const bool big : {false, true}) {
    std::string text =
        std::string("ply\nformat ") +
        (big ? "binary_big_endian" : "binary_little_endian") +
        " 1.0\nelement vertex 3\nproperty double x\n"
        "property double y\nproperty double z\nproperty float s\n"
        "property float t\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    auto put = [&](auto value) {
      char b[sizeof(value)];
      std::memcpy(b, &value, sizeof(value));
      if (big == (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__))
        std::reverse(b, b + sizeof(value));
      text.append(b, sizeof(value));
    };
    const double xyz[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.1}};
    for (int v = 0; v < 3; ++v) {
      for (double x : xyz[v]) put(x);
      put(float(v)), put(float(-v));
    }
    put(uint8_t{3}), put(int32_t{0}), put(int32_t{1}), put(int32_t{2});
    const std::string path = Write(big ? "be.ply" : "le.ply", text);
    PolygonSoup s;
    ASSERT_TRUE(ReadPolygonSoupFile(path, &s).ok()) << big;
    EXPECT_EQ(s.vertices[2].z, 0.1);
    EXPECT_EQ(At(s, "uv", 2), (std::vector<float>{2, -2}));
    std::remove(path.c_str());
  }
}

}  // namespace
}  // namespace dot
