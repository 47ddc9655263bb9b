// SPDX-License-Identifier: AGPL-3.0-or-later
// The recorded response streams of tests/golden/ (scripts/record_golden.py)
// reassembled by the C++ client's code (wire::MeshAssembler, as dotctl's
// TriangulateRemote and FillRemote use it) must give the meshes stored
// beside them, which dotctl --local computed without any wire. The Python
// client replays the same files (tests/python/test_golden.py), so the two
// clients cannot drift apart.
#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "wire/fill_wire.h"
#include "wire/wire.h"

#ifndef DOT_GOLDEN_DIR
#error "DOT_GOLDEN_DIR must name tests/golden"
#endif

namespace dot {
namespace {

using google::protobuf::ListValue;
using google::protobuf::Struct;
using google::protobuf::Value;

std::string ReadAll(const std::string& name) {
  std::ifstream in(std::string(DOT_GOLDEN_DIR) + "/" + name, std::ios::binary);
  EXPECT_TRUE(in) << "cannot open tests/golden/" << name;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// 4-byte little-endian length, then the serialized message; again.
template <typename Message>
std::vector<Message> ReadStream(const std::string& name) {
  const std::string data = ReadAll(name);
  std::vector<Message> out;
  size_t at = 0;
  while (at < data.size()) {
    EXPECT_LE(at + 4, data.size()) << "truncated length prefix";
    if (at + 4 > data.size()) break;
    const auto* b = reinterpret_cast<const unsigned char*>(data.data() + at);
    const uint32_t size =
        b[0] | b[1] << 8 | b[2] << 16 | static_cast<uint32_t>(b[3]) << 24;
    at += 4;
    EXPECT_LE(at + size, data.size()) << "truncated message";
    if (at + size > data.size()) break;
    Message m;
    EXPECT_TRUE(m.ParseFromArray(data.data() + at, static_cast<int>(size)));
    out.push_back(std::move(m));
    at += size;
  }
  return out;
}

Struct ReadJson(const std::string& name) {
  Struct s;
  const auto status =
      google::protobuf::util::JsonStringToMessage(ReadAll(name), &s);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return s;
}

const Value& Field(const Struct& s, const std::string& key) {
  auto it = s.fields().find(key);
  EXPECT_NE(it, s.fields().end()) << "no field " << key;
  static const Value kNull;
  return it == s.fields().end() ? kNull : it->second;
}

std::vector<Vec3> Points(const Value& v) {
  std::vector<Vec3> out;
  for (const Value& row : v.list_value().values()) {
    const ListValue& p = row.list_value();
    out.push_back({p.values(0).number_value(), p.values(1).number_value(),
                   p.values(2).number_value()});
  }
  return out;
}

std::vector<Triangle> Triangles(const Value& v) {
  std::vector<Triangle> out;
  for (const Value& row : v.list_value().values()) {
    const ListValue& t = row.list_value();
    out.push_back({static_cast<int32_t>(t.values(0).number_value()),
                   static_cast<int32_t>(t.values(1).number_value()),
                   static_cast<int32_t>(t.values(2).number_value())});
  }
  return out;
}

// Exact: every coordinate bit for bit.
void ExpectSameMesh(const MeshData& got, const std::vector<Vec3>& vertices,
                    const std::vector<Triangle>& triangles) {
  ASSERT_EQ(got.vertices.size(), vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) {
    EXPECT_EQ(std::memcmp(&got.vertices[i], &vertices[i], sizeof(Vec3)), 0)
        << "vertex " << i;
  }
  EXPECT_EQ(got.triangles, triangles);
}

TEST(GoldenStreamTest, TriangulateStreamReassemblesToTheLocalResult) {
  const auto messages =
      ReadStream<v1::TriangulateResponse>("triangulate.stream");
  const Struct doc = ReadJson("triangulate.json");
  const Struct& request = Field(doc, "request").struct_value();
  const Struct& expected = Field(doc, "expected").struct_value();
  ASSERT_TRUE(
      Field(Field(request, "options").struct_value(), "omit_input_vertices")
          .bool_value());
  const std::vector<Vec3> input = Points(Field(request, "points"));

  // TriangulateRemote's loop, over the recorded messages.
  wire::MeshAssembler assembler;
  v1::Summary summary;
  bool have_summary = false;
  int chunks = 0;
  for (const auto& m : messages) {
    EXPECT_EQ(m.id(), "golden");
    if (m.has_mesh()) {
      ASSERT_TRUE(assembler.Add(m.mesh()).ok());
      ++chunks;
    }
    if (m.has_summary()) {
      summary = m.summary();
      have_summary = true;
    }
  }
  ASSERT_TRUE(have_summary);
  EXPECT_GE(chunks, 3);  // recorded with 1 KiB chunks
  EXPECT_EQ(summary.status(), v1::RESULT_STATUS_OK);
  EXPECT_EQ(summary.inserted_count(),
            Field(expected, "inserted_count").number_value());
  // The server left the input out: the first chunk starts after it.
  for (const auto& m : messages) {
    if (!m.has_mesh()) continue;
    EXPECT_EQ(m.mesh().first_vertex(), input.size());
    break;
  }
  MeshData mesh;
  const Status s = assembler.Finish(summary, input, &mesh);
  ASSERT_TRUE(s.ok()) << s.message;
  ExpectSameMesh(mesh, Points(Field(expected, "vertices")),
                 Triangles(Field(expected, "triangles")));
}

TEST(GoldenStreamTest, TriangulateLoopsStreamCarriesLoopsAndBridges) {
  const auto messages =
      ReadStream<v1::TriangulateResponse>("triangulate_loops.stream");
  const Struct doc = ReadJson("triangulate_loops.json");
  const Struct& request = Field(doc, "request").struct_value();
  const Struct& expected = Field(doc, "expected").struct_value();
  const std::vector<Vec3> input = Points(Field(request, "points"));
  wire::MeshAssembler assembler;
  v1::Summary summary;
  for (const auto& m : messages) {
    if (m.has_mesh()) {
      ASSERT_TRUE(assembler.Add(m.mesh()).ok());
    }
    if (m.has_summary()) summary = m.summary();
  }
  ASSERT_EQ(summary.status(), v1::RESULT_STATUS_OK);
  auto numbers = [](const Value& v) {
    std::vector<uint32_t> out;
    for (const Value& x : v.list_value().values()) {
      out.push_back(static_cast<uint32_t>(x.number_value()));
    }
    return out;
  };
  EXPECT_EQ(std::vector<uint32_t>(summary.loop_sizes().begin(),
                                  summary.loop_sizes().end()),
            numbers(Field(expected, "loop_sizes")));
  EXPECT_EQ(std::vector<uint32_t>(summary.loop().begin(), summary.loop().end()),
            numbers(Field(expected, "loop")));
  EXPECT_EQ(
      std::vector<uint32_t>(summary.bridges().begin(), summary.bridges().end()),
      numbers(Field(expected, "bridges")));
  EXPECT_EQ(summary.bridges_size(), 4);  // two bridges join three loops
  MeshData mesh;
  const Status s = assembler.Finish(summary, input, &mesh);
  ASSERT_TRUE(s.ok()) << s.message;
  ExpectSameMesh(mesh, Points(Field(expected, "vertices")),
                 Triangles(Field(expected, "triangles")));
}

TEST(GoldenStreamTest, FillHolesStreamReassemblesToTheLocalResult) {
  const auto messages = ReadStream<v1::FillHolesResponse>("fill_holes.stream");
  const Struct doc = ReadJson("fill_holes.json");
  const Struct& expected = Field(doc, "expected").struct_value();
  ASSERT_FALSE(messages.empty());
  ASSERT_TRUE(messages.back().has_report());  // last, as the proto says

  // FillRemote's loop, over the recorded messages.
  wire::MeshAssembler assembler;
  v1::FillReport report;
  int progress = 0, vertex_chunks = 0, triangle_chunks = 0;
  for (const auto& m : messages) {
    switch (m.payload_case()) {
      case v1::FillHolesResponse::kProgress:
        ++progress;
        break;
      case v1::FillHolesResponse::kMesh:
        ASSERT_TRUE(assembler.Add(m.mesh()).ok());
        vertex_chunks += m.mesh().vertices_size() > 0;
        triangle_chunks += m.mesh().triangles_size() > 0;
        break;
      case v1::FillHolesResponse::kReport:
        report = m.report();
        break;
      default:
        break;
    }
  }
  EXPECT_GE(progress, 1);
  EXPECT_GE(vertex_chunks, 2);  // recorded with 1 KiB chunks
  EXPECT_GE(triangle_chunks, 2);
  EXPECT_EQ(report.filled(), Field(expected, "filled").number_value());
  EXPECT_EQ(report.added_vertices(),
            Field(expected, "added_vertices").number_value());
  EXPECT_TRUE(report.closed());
  MeshData mesh;
  const Status s =
      assembler.Finish(report.input_vertices() + report.added_vertices(),
                       report.input_faces() + report.added_faces(), {}, &mesh);
  ASSERT_TRUE(s.ok()) << s.message;
  ExpectSameMesh(mesh, Points(Field(expected, "vertices")),
                 Triangles(Field(expected, "faces")));
}

// The checks that make a bad stream fail, on the recorded one cut short or
// shuffled (the Python tests make the same cuts and expect the same words).
TEST(GoldenStreamTest, DamagedStreamsAreRefused) {
  const auto messages =
      ReadStream<v1::TriangulateResponse>("triangulate.stream");
  const Struct doc = ReadJson("triangulate.json");
  const std::vector<Vec3> input =
      Points(Field(Field(doc, "request").struct_value(), "points"));
  const v1::Summary& summary = messages.back().summary();
  std::vector<v1::MeshChunk> chunks;  // inserted vertices, then triangles
  for (const auto& m : messages) {
    if (m.has_mesh()) chunks.push_back(m.mesh());
  }
  ASSERT_GE(chunks.size(), 3u);
  ASSERT_GT(chunks.front().vertices_size(), 0);
  ASSERT_GT(chunks.back().triangles_size(), 0);
  {  // the last chunk lost
    wire::MeshAssembler a;
    for (size_t i = 0; i + 1 < chunks.size(); ++i) {
      ASSERT_TRUE(a.Add(chunks[i]).ok());
    }
    MeshData mesh;
    const Status s = a.Finish(summary, input, &mesh);
    EXPECT_NE(s.message.find("incomplete mesh"), std::string::npos)
        << s.message;
  }
  {  // the input unknown to the client
    wire::MeshAssembler a;
    for (const auto& c : chunks) ASSERT_TRUE(a.Add(c).ok());
    MeshData mesh;
    const Status s = a.Finish(summary, {}, &mesh);
    EXPECT_NE(s.message.find("input vertices are known"), std::string::npos)
        << s.message;
  }
  {  // a vertex chunk twice
    wire::MeshAssembler a;
    ASSERT_TRUE(a.Add(chunks[0]).ok());
    const Status s = a.Add(chunks[0]);
    EXPECT_NE(s.message.find("out of order"), std::string::npos) << s.message;
  }
  {  // triangle chunks swapped
    wire::MeshAssembler a;
    ASSERT_TRUE(a.Add(chunks[0]).ok());
    const Status s = a.Add(chunks.back());
    EXPECT_NE(s.message.find("out of order: triangle"), std::string::npos)
        << s.message;
  }
}

// The patches answer (FILL_ANSWER_PATCHES) as the C++ client reads it
// (wire::PatchReader, as FillRemote uses it): the patch of a hole whose
// boundary edge protection split, over several 1 KiB messages, equal to the
// patch derived from dotctl --local's whole mesh; applied to the mesh as
// sent it gives that whole mesh.
TEST(GoldenStreamTest, FillHolesPatchesReassembleAndRebuildTheLocalMesh) {
  const auto messages =
      ReadStream<v1::FillHolesResponse>("fill_holes_patches.stream");
  const Struct doc = ReadJson("fill_holes_patches.json");
  const Struct& request = Field(doc, "request").struct_value();
  const Struct& expected = Field(doc, "expected").struct_value();
  ASSERT_FALSE(messages.empty());
  ASSERT_TRUE(messages.back().has_report());
  const std::vector<Vec3> sent = Points(Field(request, "vertices"));
  wire::PatchReader reader(sent.size());
  int progress = 0, patch_messages = 0;
  for (const auto& m : messages) {
    EXPECT_FALSE(m.has_mesh());  // only what is new
    progress += m.has_progress();
    if (!m.has_patch()) continue;
    ++patch_messages;
    EXPECT_EQ(m.patch().hole(), 1);
    const Status s = reader.Add(m.patch());
    ASSERT_TRUE(s.ok()) << s.message;
  }
  EXPECT_GE(progress, 1);
  EXPECT_GE(patch_messages, 2);  // one patch, continued
  const v1::FillReport& report = messages.back().report();
  EXPECT_EQ(report.version(), 2u);
  EXPECT_EQ(report.filled(), Field(expected, "filled").number_value());
  EXPECT_EQ(report.added_vertices(),
            Field(expected, "added_vertices").number_value());
  ASSERT_EQ(report.holes_size(), 2);
  EXPECT_EQ(report.holes(0).status(), v1::HOLE_STATUS_SKIPPED);
  EXPECT_EQ(report.holes(1).status(), v1::HOLE_STATUS_FILLED);
  EXPECT_EQ(report.holes(1).escalation(), v1::ESCALATION_PROTECTED_EDGES);
  // The loop's size and place (HoleReport fields 22-24).
  EXPECT_EQ(report.holes(1).centroid_size(), 3);
  EXPECT_GT(report.holes(1).perimeter(), 0);
  EXPECT_GT(report.holes(0).diameter(), report.holes(1).diameter());

  const auto& want = Field(expected, "patches").list_value();
  const std::vector<SentPatch>& got = reader.patches();
  ASSERT_EQ(got.size(), static_cast<size_t>(want.values_size()));
  const Struct& w = want.values(0).struct_value();
  EXPECT_EQ(got[0].hole, Field(w, "hole").number_value());
  EXPECT_EQ(got[0].first_vertex, static_cast<int32_t>(sent.size()));
  ExpectSameMesh(MeshData{got[0].new_vertices, got[0].faces},
                 Points(Field(w, "vertices")), Triangles(Field(w, "faces")));
  const auto& replaced = Field(w, "replaced_faces").list_value();
  ASSERT_EQ(got[0].replaced_faces.size(),
            static_cast<size_t>(replaced.values_size()));
  for (int k = 0; k < replaced.values_size(); ++k) {
    const Struct& r = replaced.values(k).struct_value();
    EXPECT_EQ(got[0].replaced_faces[k], Field(r, "face").number_value());
    EXPECT_EQ(got[0].replacements[k], Triangles(Field(r, "triangles")));
  }

  // Applied to the mesh as sent: the whole mesh of the local run.
  std::vector<Vec3> vertices = sent;
  std::vector<Triangle> faces;
  const std::vector<Triangle> sent_faces = Triangles(Field(request, "faces"));
  for (size_t f = 0; f < sent_faces.size(); ++f) {
    const auto& ids = got[0].replaced_faces;
    if (std::find(ids.begin(), ids.end(), static_cast<int32_t>(f)) ==
        ids.end()) {
      faces.push_back(sent_faces[f]);
    }
  }
  for (const SentPatch& p : got) {
    vertices.insert(vertices.end(), p.new_vertices.begin(),
                    p.new_vertices.end());
    for (const auto& pieces : p.replacements) {
      faces.insert(faces.end(), pieces.begin(), pieces.end());
    }
    faces.insert(faces.end(), p.faces.begin(), p.faces.end());
  }
  const Struct& whole = Field(expected, "whole_mesh").struct_value();
  auto canonical = [](std::vector<Triangle> t) {
    for (Triangle& x : t) {
      std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  ExpectSameMesh(MeshData{vertices, canonical(faces)},
                 Points(Field(whole, "vertices")),
                 canonical(Triangles(Field(whole, "faces"))));

  // A damaged stream is named: the first patch message twice.
  std::vector<v1::HolePatch> damaged;
  for (const auto& m : messages) {
    if (m.has_patch()) damaged.push_back(m.patch());
  }
  damaged.insert(damaged.begin() + 1, damaged.front());
  wire::PatchReader again(sent.size());
  Status s = OkStatus();
  for (const auto& m : damaged) {
    if (s.ok()) s = again.Add(m);
  }
  EXPECT_NE(s.message.find("does not continue where the last message ended"),
            std::string::npos)
      << s.message;
}

// The recorded uploads are what FillRequestWriter writes for the same mesh
// and options (1 KiB slices), and FillRequestReader reads them back.
TEST(GoldenStreamTest, FillHolesUploadsAreWhatTheWriterWrites) {
  for (const std::string name : {"fill_holes", "fill_holes_patches"}) {
    const auto recorded = ReadStream<v1::FillHolesRequest>(name + ".requests");
    const Struct doc = ReadJson(name + ".json");
    const Struct& request = Field(doc, "request").struct_value();
    ASSERT_FALSE(recorded.empty()) << name;
    PolygonSoup soup;
    soup.vertices = Points(Field(request, "vertices"));
    for (const Triangle& t : Triangles(Field(request, "faces"))) {
      soup.faces.push_back({t[0], t[1], t[2]});
    }
    wire::FillRequestWriter writer(
        recorded[0].id(), recorded[0].options(), soup,
        static_cast<size_t>(Field(request, "upload_bytes").number_value()));
    size_t k = 0;
    for (v1::FillHolesRequest m; writer.Next(&m); ++k) {
      ASSERT_LT(k, recorded.size()) << name;
      EXPECT_EQ(m.SerializeAsString(), recorded[k].SerializeAsString())
          << name << " message " << k;
    }
    EXPECT_EQ(k, recorded.size()) << name;
    wire::FillRequestReader reader(1 << 20, 1 << 20);
    for (const auto& m : recorded) {
      const Status s = reader.Add(m);
      ASSERT_TRUE(s.ok()) << name << ": " << s.message;
    }
    PolygonSoup read;
    ASSERT_TRUE(reader.Finish(&read).ok()) << name;
    EXPECT_EQ(read.faces, soup.faces) << name;
    ASSERT_EQ(read.vertices.size(), soup.vertices.size()) << name;
    for (size_t v = 0; v < soup.vertices.size(); ++v) {
      EXPECT_EQ(read.vertices[v], soup.vertices[v]) << name << " " << v;
    }
  }
  const auto patches =
      ReadStream<v1::FillHolesRequest>("fill_holes_patches.requests");
  EXPECT_EQ(patches[0].options().answer(), v1::FILL_ANSWER_PATCHES);
}

}  // namespace
}  // namespace dot
