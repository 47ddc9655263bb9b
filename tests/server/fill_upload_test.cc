// SPDX-License-Identifier: AGPL-3.0-or-later
// FillUpload without a socket: messages added under the server's limits,
// the mesh's memory charged against the server-wide FillHoles memory as it
// arrives (two uploads share it) and given back with the upload, a slow
// upload bound by the job's deadline.
#include "rpc/fill_upload.h"

#include <gtest/gtest.h>

#include <memory>

#include "fixtures/runner_fixture.h"

namespace dot::server {
namespace {

using testing::kNoDeadline;

// n vertices of a fan around vertex 0, as one message.
v1::FillHolesRequest Fan(int n) {
  v1::FillHolesRequest m;
  for (int i = 0; i < n; ++i) {
    m.mutable_mesh()->add_vertices(i);
    m.mutable_mesh()->add_vertices(i % 7);
    m.mutable_mesh()->add_vertices(0);
  }
  return m;
}

TEST(FillUploadTest, TheMeshIsChargedAsItArrivesAndGivenBackWithTheUpload) {
  ServiceOptions o;
  // Room for one 10,000-vertex mesh (100 bytes a vertex), not two.
  o.fill_memory_bytes = 1500000;
  testing::Runner r(o);
  grpc::Status error;
  auto a = r.runner.AdmitTask("FillHoles", "a", 0, kNoDeadline, &error);
  auto b = r.runner.AdmitTask("FillHoles", "b", 0, kNoDeadline, &error);
  auto first = std::make_unique<FillUpload>(&r.runner);
  ASSERT_TRUE(first->Add(Fan(10000), *a).ok());
  FillUpload second(&r.runner);
  const grpc::Status full = second.Add(Fan(10000), *b);
  EXPECT_EQ(full.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(full.error_message().find("taken by other calls"),
            std::string::npos)
      << full.error_message();
  first.reset();  // the first call ends: its memory is free again
  FillUpload third(&r.runner);
  EXPECT_TRUE(third.Add(Fan(10000), *b).ok());
  // A mesh larger than the whole budget is told so, not "retry later".
  FillUpload huge(&r.runner);
  const grpc::Status never = huge.Add(Fan(20000), *a);
  EXPECT_NE(never.error_message().find("more than the server's memory"),
            std::string::npos)
      << never.error_message();
  r.runner.Answered(*a, grpc::Status::OK);
  r.runner.Answered(*b, grpc::Status::OK);
}

TEST(FillUploadTest, ASlowUploadIsBoundByTheJobsDeadlineAndStops) {
  testing::Runner r;
  grpc::Status error;
  auto late = r.runner.AdmitTask(
      "FillHoles", "late", 0,
      std::chrono::system_clock::now() - std::chrono::seconds(1), &error);
  FillUpload upload(&r.runner);
  EXPECT_EQ(upload.Add(Fan(3), *late).error_code(),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_EQ(late->stop.load(), StopReason::kClientDeadline);
  auto cancelled = r.runner.AdmitTask("FillHoles", "c", 0, kNoDeadline, &error);
  cancelled->Stop(StopReason::kDrain);
  EXPECT_EQ(upload.Add(Fan(3), *cancelled).error_code(),
            grpc::StatusCode::UNAVAILABLE);
  r.runner.Answered(*late, grpc::Status::OK);
  r.runner.Answered(*cancelled, grpc::Status::OK);
}

}  // namespace
}  // namespace dot::server
