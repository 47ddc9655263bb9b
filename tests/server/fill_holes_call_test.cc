// SPDX-License-Identifier: AGPL-3.0-or-later
// The FillHoles use case without a socket: options refused before any mesh
// is read, the server's limits applied, and the answer's messages (the mesh
// in chunks or the patches, then the report) made from the fill.
#include "rpc/fill_holes_call.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "fixtures/meshes.h"

namespace dot::server {
namespace {

// Every message of the answer, the report last.
std::vector<v1::FillHolesResponse> Answer(FillHolesCall& call,
                                          size_t chunk_bytes) {
  std::vector<v1::FillHolesResponse> out;
  while (!call.done()) {
    out.emplace_back();
    call.Next("id-7", chunk_bytes, &out.back());
    if (out.size() > 10000) break;  // never: a runaway answer fails below
  }
  return out;
}

TEST(FillHolesCallTest, BadOptionsAreRefusedBeforeAnyMeshIsRead) {
  FillHolesCall call;
  v1::FillOptions wire;
  wire.set_density(1000);
  const Status s = call.Configure(wire, ServiceOptions{}, 2);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("density"), std::string::npos) << s.message;
}

TEST(FillHolesCallTest, TheWholeMeshComesInChunksThenTheReport) {
  FillHolesCall call;
  ASSERT_TRUE(call.Configure(v1::FillOptions{}, ServiceOptions{}, 1).ok());
  const MeshData mesh = testing::HoleyTorus(24, 12, 3, 6);
  std::string log;
  ASSERT_TRUE(call.Run(ToSoup(mesh), Control{}, nullptr, &log).ok());
  EXPECT_NE(log.find("holes=3 filled=3"), std::string::npos) << log;
  const auto messages = Answer(call, 1024);
  ASSERT_GE(messages.size(), 3u);  // 1 KiB chunks: several of them
  size_t vertices = 0;
  for (size_t i = 0; i + 1 < messages.size(); ++i) {
    EXPECT_EQ(messages[i].id(), "id-7");
    ASSERT_TRUE(messages[i].has_mesh()) << i;
    EXPECT_EQ(messages[i].mesh().first_vertex(), vertices);
    vertices += messages[i].mesh().vertices_size() / 3;
  }
  EXPECT_GE(vertices, mesh.vertices.size());
  ASSERT_TRUE(messages.back().has_report());
  EXPECT_EQ(messages.back().report().holes_size(), 3);
}

TEST(FillHolesCallTest, PatchesAloneAreTheAnswerWhenAsked) {
  FillHolesCall call;
  v1::FillOptions wire;
  wire.set_answer(v1::FILL_ANSWER_PATCHES);
  ASSERT_TRUE(call.Configure(wire, ServiceOptions{}, 1).ok());
  const MeshData mesh = testing::HoleyTorus(24, 12, 3, 6);
  std::string log;
  ASSERT_TRUE(call.Run(ToSoup(mesh), Control{}, nullptr, &log).ok());
  const auto messages = Answer(call, 1 << 20);
  int patches = 0;
  for (const auto& m : messages) {
    EXPECT_FALSE(m.has_mesh()) << "the mesh is not sent again";
    if (m.has_patch()) {
      ++patches;
      EXPECT_GT(m.patch().faces_size(), 0);
    }
  }
  EXPECT_EQ(patches, 3);  // one per hole
  ASSERT_TRUE(messages.back().has_report());
}

TEST(FillHolesCallTest, AStoppedFillIsItsStatusAndTheLogSaysWhatArrived) {
  FillHolesCall call;
  ASSERT_TRUE(call.Configure(v1::FillOptions{}, ServiceOptions{}, 1).ok());
  std::atomic<bool> cancel{true};
  Control control;
  control.cancel = &cancel;
  std::string log;
  const Status s = call.Run(ToSoup(testing::HoleyTorus(24, 12, 3, 6)), control,
                            nullptr, &log);
  EXPECT_EQ(s.code, StatusCode::kCancelled);
  EXPECT_NE(log.find("vertices="), std::string::npos) << log;
}

}  // namespace
}  // namespace dot::server
