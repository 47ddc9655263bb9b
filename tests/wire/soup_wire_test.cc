// SPDX-License-Identifier: AGPL-3.0-or-later
// A polygon soup with attribute channels through MeshChunk slices and back,
// whatever the slice size; malformed slices refused by name; patches with
// corner values through HolePatch messages and back.
#include "wire/soup_wire.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "wire/fill_wire.h"

namespace dot::wire {
namespace {

// A 3 x 3 grid of quads with one quad split in two triangles, a colour
// per vertex and UVs per corner with a seam (the right column's own).
PolygonSoup Grid() {
  PolygonSoup s;
  for (int i = 0; i <= 3; ++i) {
    for (int j = 0; j <= 3; ++j) s.vertices.push_back({1.0 * i, 1.0 * j, 0});
  }
  auto id = [](int i, int j) { return i * 4 + j; };
  AttributeChannel color{"color", 3, {}, {}}, uv{"uv", 2, {}, {}};
  for (size_t v = 0; v < s.vertices.size(); ++v) {
    color.values.insert(color.values.end(),
                        {0.1f * static_cast<float>(v), 0.5f, 1.0f});
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i == 1 && j == 1) {
        s.faces.push_back({id(1, 1), id(2, 1), id(2, 2)});
        s.faces.push_back({id(1, 1), id(2, 2), id(1, 2)});
      } else {
        s.faces.push_back(
            {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  }
  for (FaceView f : s.faces) {
    const float seam = s.vertices[f[0]].x >= 2 ? 1.0f : 0.0f;
    for (int32_t v : f) {
      uv.indices.push_back(static_cast<int32_t>(uv.entries()));
      uv.values.insert(uv.values.end(),
                       {static_cast<float>(s.vertices[v].x) / 3 + seam,
                        static_cast<float>(s.vertices[v].y) / 3});
    }
  }
  s.attributes = {color, uv};
  return s;
}

std::vector<v1::MeshChunk> Slices(const PolygonSoup& soup, size_t bytes) {
  SoupChunkWriter writer(soup, bytes);
  std::vector<v1::MeshChunk> out;
  v1::MeshChunk c;
  while (writer.Next(&c)) out.push_back(c);
  return out;
}

Status Read(const std::vector<v1::MeshChunk>& slices, PolygonSoup* soup) {
  SoupChunkReader reader(1000, 1000);
  for (size_t i = 0; i < slices.size(); ++i) {
    const Status s = reader.Add(slices[i], "slice " + std::to_string(i));
    if (!s.ok()) return s;
  }
  return reader.Finish(soup);
}

void ExpectSameSoup(const PolygonSoup& a, const PolygonSoup& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (size_t v = 0; v < a.vertices.size(); ++v) {
    EXPECT_EQ(a.vertices[v].x, b.vertices[v].x);
    EXPECT_EQ(a.vertices[v].y, b.vertices[v].y);
  }
  EXPECT_EQ(a.faces, b.faces);
  ASSERT_EQ(a.attributes.size(), b.attributes.size());
  for (size_t c = 0; c < a.attributes.size(); ++c) {
    EXPECT_EQ(a.attributes[c].name, b.attributes[c].name);
    EXPECT_EQ(a.attributes[c].dims, b.attributes[c].dims);
    EXPECT_EQ(a.attributes[c].values, b.attributes[c].values);
    EXPECT_EQ(a.attributes[c].indices, b.attributes[c].indices);
  }
}

TEST(SoupWireTest, ASoupComesBackWholeWhateverTheSliceSize) {
  const PolygonSoup sent = Grid();
  for (size_t bytes : {64, 200, 1 << 20}) {
    const auto slices = Slices(sent, bytes);
    if (bytes == 64) {
      EXPECT_GT(slices.size(), 10u);  // every part sliced
    }
    PolygonSoup got;
    const Status s = Read(slices, &got);
    ASSERT_TRUE(s.ok()) << bytes << ": " << s.message;
    ExpectSameSoup(sent, got);
  }
}

TEST(SoupWireTest, MalformedChannelsAreRefusedByName) {
  const PolygonSoup sent = Grid();
  const auto good = Slices(sent, 1 << 20);  // vertices, faces, 3 channel parts
  ASSERT_EQ(good.size(), 5u);
  auto refused = [](std::vector<v1::MeshChunk> slices) {
    PolygonSoup soup;
    return Read(slices, &soup).message;
  };
  auto expect = [&](std::vector<v1::MeshChunk> slices,
                    const std::string& what) {
    const std::string message = refused(std::move(slices));
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  {  // a channel before any face
    auto s = good;
    *s[0].mutable_attribute() = good[2].attribute();
    expect(s, "before any face");
  }
  {  // faces after attributes
    auto s = good;
    s.push_back(good[1]);
    expect(s, "faces after attributes");
  }
  {  // more per-vertex entries than vertices
    auto s = good;
    s[2].mutable_attribute()->add_values(1);
    s[2].mutable_attribute()->add_values(1);
    s[2].mutable_attribute()->add_values(1);
    expect(s, "more entries than the mesh has vertices");
  }
  {  // too few corner indices
    auto s = good;
    s[4].mutable_attribute()->mutable_indices()->RemoveLast();
    expect(s, "'uv' is per_corner but");
  }
  {  // an index naming no entry
    auto s = good;
    s[4].mutable_attribute()->set_indices(0, 9999);
    expect(s, "names entry 9999");
  }
  {  // a channel sent twice, and out of order
    auto s = good;
    s.push_back(good[2]);
    expect(s, "'color' is sent twice");
    s = good;
    s[3].mutable_attribute()->set_first_value(1);
    expect(s, "starts at entry 1");
  }
  {  // dims, non-finite values, no name
    auto s = good;
    s[2].mutable_attribute()->set_dims(0);
    expect(s, "1 to 16 are allowed");
    s = good;
    s[2].mutable_attribute()->set_values(4, std::nanf(""));
    expect(s, "entry 1 is not finite");
    s = good;
    s[2].mutable_attribute()->clear_name();
    expect(s, "needs a name");
  }
  {  // at most 16 channels
    std::vector<v1::MeshChunk> s(good.begin(), good.begin() + 2);
    for (int c = 0; c < 17; ++c) {
      v1::MeshChunk& m = s.emplace_back(good[2]);
      m.mutable_attribute()->set_name("c" + std::to_string(c));
    }
    expect(s, "more than 16 attribute channels");
  }
}

TEST(SoupWireTest, PatchCornerValuesSurviveAnySplitIntoMessages) {
  SentPatch p;
  p.hole = 3;
  p.first_vertex = 10;
  p.new_vertices = {{0, 0, 1}, {1, 0, 1}};
  for (int k = 0; k < 7; ++k) p.faces.push_back({k, 10, 11});
  p.replaced_faces = {4, 6};
  p.replacements = {{{0, 1, 10}, {1, 2, 10}}, {{5, 6, 11}}};
  PatchChannel uv{"uv", 2, {}, {}};
  for (int i = 0; i < 2 * 3 * 7; ++i) uv.faces.push_back(0.5f * i);
  for (int i = 0; i < 2 * 3 * 3; ++i) uv.replaced.push_back(-0.25f * i);
  p.attributes = {uv};
  const std::vector<SentPatch> patches = {p};
  for (size_t bytes : {1, 40, 1 << 20}) {
    PatchWriter writer(patches, bytes);
    PatchReader reader(10);
    v1::HolePatch m;
    int messages = 0;
    while (writer.Next(&m)) {
      ++messages;
      const Status s = reader.Add(m);
      ASSERT_TRUE(s.ok()) << s.message;
    }
    if (bytes == 1) {
      EXPECT_GT(messages, 5);
    }
    ASSERT_EQ(reader.patches().size(), 1u);
    const SentPatch& got = reader.patches()[0];
    EXPECT_EQ(got.faces, p.faces);
    EXPECT_EQ(got.replacements, p.replacements);
    ASSERT_EQ(got.attributes.size(), 1u);
    EXPECT_EQ(got.attributes[0].name, "uv");
    EXPECT_EQ(got.attributes[0].faces, uv.faces);
    EXPECT_EQ(got.attributes[0].replaced, uv.replaced);
  }
  // Values that do not match the message's corners are refused.
  PatchWriter writer(patches, 1 << 20);
  v1::HolePatch m;
  ASSERT_TRUE(writer.Next(&m));
  m.mutable_attributes(0)->mutable_faces()->RemoveLast();
  PatchReader reader(10);
  const Status s = reader.Add(m);
  EXPECT_NE(s.message.find("'uv' does not match"), std::string::npos)
      << s.message;
}

}  // namespace
}  // namespace dot::wire
