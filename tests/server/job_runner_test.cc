// SPDX-License-Identifier: AGPL-3.0-or-later
// JobRunner without a socket: one admission path (id, deadline, drain; a
// polygon's own checks on top), one run path for polygons and other work
// (queued or inline, cancel and deadline before the work, exceptions as
// RESOURCE_EXHAUSTED, who stopped a run at its deadline), drains.
#include <gtest/gtest.h>

#include <condition_variable>
#include <future>
#include <mutex>
#include <new>

#include "dot/dot.h"
#include "fixtures/runner_fixture.h"
#include "rpc/job.h"

namespace dot::server {
namespace {

using testing::kNoDeadline;

// Runs `work` on the pool and waits for on_done.
Status RunOnPool(JobRunner& runner, const std::shared_ptr<Job>& job,
                 JobRunner::Work work) {
  std::promise<void> done;
  job->on_done = [&done] { done.set_value(); };
  EXPECT_TRUE(runner.Start(job, /*may_run_here=*/false, std::move(work)));
  done.get_future().wait();
  return job->result.status;
}

TEST(JobRunnerTest, AdmissionChecksTheIdAndTracksTheJobUntilAnswered) {
  testing::Runner r;
  grpc::Status error;
  auto refused = r.runner.AdmitTask("FillHoles", std::string(300, 'x'), 0,
                                    kNoDeadline, &error);
  EXPECT_EQ(error.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(error.error_message().find("at most 256"), std::string::npos);
  r.runner.Answered(*refused, error);

  auto job = r.runner.AdmitTask("FillHoles", "a", 0, kNoDeadline, &error);
  ASSERT_TRUE(error.ok());
  EXPECT_EQ(r.runner.inflight(), 1);
  r.runner.Answered(*job, grpc::Status::OK);
  EXPECT_EQ(r.runner.inflight(), 0);
}

TEST(JobRunnerTest, TheDeadlineIsTheSmallestOfLimitBudgetAndClient) {
  ServiceOptions o;
  o.max_compute_ms = 10000;
  testing::Runner r(o);
  grpc::Status error;
  auto budget = r.runner.AdmitTask("T", "", 2000, kNoDeadline, &error);
  EXPECT_EQ(budget->deadline - budget->arrived, std::chrono::seconds(2));
  EXPECT_TRUE(budget->deadline_is_limit);
  auto over = r.runner.AdmitTask("T", "", 50000, kNoDeadline, &error);
  EXPECT_EQ(over->deadline - over->arrived, std::chrono::seconds(10));
  auto client = r.runner.AdmitTask(
      "T", "", 0, std::chrono::system_clock::now() + std::chrono::seconds(1),
      &error);
  EXPECT_LE(client->deadline - client->arrived, std::chrono::seconds(1));
  EXPECT_FALSE(client->deadline_is_limit);
  for (const auto& j : {budget, over, client}) {
    r.runner.Answered(*j, grpc::Status::OK);
  }
}

TEST(JobRunnerTest, APolygonIsAdmittedThroughTheSamePathPlusItsOwnChecks) {
  ServiceOptions o;
  o.max_vertices = 10;
  testing::Runner r(o);
  v1::TriangulateRequest request;
  request.set_id("p");
  for (int i = 0; i < 12; ++i) {
    request.mutable_polygon()->add_coordinates(std::cos(i * 0.5));
    request.mutable_polygon()->add_coordinates(std::sin(i * 0.5));
    request.mutable_polygon()->add_coordinates(0.1 * (i % 2));
  }
  grpc::Status error;
  auto big = r.runner.Admit(request, kNoDeadline, "Triangulate", &error);
  EXPECT_EQ(error.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(error.error_message().find("at most 10"), std::string::npos);
  EXPECT_EQ(r.runner.inflight(), 0);  // refused: never tracked
  r.runner.Answered(*big, error);

  request.mutable_polygon()->mutable_coordinates()->Truncate(3 * 8);
  auto job = r.runner.Admit(request, kNoDeadline, "Triangulate", &error);
  ASSERT_TRUE(error.ok()) << error.error_message();
  EXPECT_EQ(job->id, "p");
  // Inline: on_done has run when Start returns.
  bool done = false;
  job->on_done = [&done] { done = true; };
  ASSERT_TRUE(r.runner.Start(job, /*may_run_here=*/true));
  EXPECT_TRUE(done);
  ASSERT_TRUE(job->result.status.ok()) << job->result.status.message;
  EXPECT_EQ(job->result.triangles.size(), 6u);
  r.runner.Answered(*job, grpc::Status::OK);
}

TEST(JobRunnerTest, WorkRunsWithTheJobsControlAndItsFailuresAreItsStatus) {
  testing::Runner r;
  grpc::Status error;
  auto job = r.runner.AdmitTask("T", "w", 3000, kNoDeadline, &error);
  const std::atomic<bool>* seen_cancel = nullptr;
  Clock::time_point seen_deadline{};
  const Status s = RunOnPool(r.runner, job, [&](Job&, const Control& c) {
    seen_cancel = c.cancel;
    seen_deadline = c.deadline;
    return OkStatus();
  });
  EXPECT_TRUE(s.ok());
  EXPECT_TRUE(job->ran);
  EXPECT_EQ(seen_cancel, &job->cancel);
  EXPECT_EQ(seen_deadline, job->deadline);
  r.runner.Answered(*job, grpc::Status::OK);

  auto throws = r.runner.AdmitTask("T", "x", 0, kNoDeadline, &error);
  const Status oom = RunOnPool(r.runner, throws, [](Job&, const Control&) {
    throw std::bad_alloc();
    return OkStatus();
  });
  EXPECT_EQ(oom.code, StatusCode::kResourceExhausted);
  EXPECT_NE(oom.message.find("computation failed"), std::string::npos);
  r.runner.Answered(*throws, grpc::Status::OK);
}

TEST(JobRunnerTest, AStopBeforeTheWorkStartsMeansItNeverRuns) {
  testing::Runner r;
  grpc::Status error;
  bool ran = false;
  auto work = [&ran](Job&, const Control&) {
    ran = true;
    return OkStatus();
  };
  auto cancelled = r.runner.AdmitTask("T", "c", 0, kNoDeadline, &error);
  cancelled->Stop(StopReason::kClientCancel);
  EXPECT_EQ(RunOnPool(r.runner, cancelled, work).message,
            "cancelled while queued");
  r.runner.Answered(*cancelled, grpc::Status::OK);

  auto late = r.runner.AdmitTask(
      "T", "d", 0, std::chrono::system_clock::now() - std::chrono::seconds(1),
      &error);
  EXPECT_EQ(RunOnPool(r.runner, late, work).code,
            StatusCode::kDeadlineExceeded);
  EXPECT_EQ(late->stop.load(), StopReason::kClientDeadline);
  r.runner.Answered(*late, grpc::Status::OK);
  EXPECT_FALSE(ran);
}

TEST(JobRunnerTest, ADeadlineTheWorkMeetsIsChargedToWhoeverSetIt) {
  testing::Runner r;
  grpc::Status error;
  auto job = r.runner.AdmitTask("T", "b", 60000, kNoDeadline, &error);
  RunOnPool(r.runner, job, [](Job&, const Control&) {
    return MakeStatus(StatusCode::kDeadlineExceeded, "deadline exceeded");
  });
  EXPECT_EQ(job->stop.load(), StopReason::kServerBudget);
  r.runner.Answered(*job, grpc::Status::OK);
}

TEST(JobRunnerTest, ADrainRefusesNewJobsAndReachesTheAdmittedOnes) {
  testing::Runner r;
  grpc::Status error;
  auto job = r.runner.AdmitTask("T", "a", 0, kNoDeadline, &error);
  int drained = 0;
  r.runner.SetOnDrain(job.get(), [&drained] { ++drained; });
  r.runner.StartDraining();
  EXPECT_EQ(drained, 1);
  auto late = r.runner.AdmitTask("T", "b", 0, kNoDeadline, &error);
  EXPECT_EQ(error.error_code(), grpc::StatusCode::UNAVAILABLE);
  r.runner.CancelAllForDrain();
  EXPECT_TRUE(job->cancel);
  EXPECT_EQ(job->stop.load(), StopReason::kDrain);
  r.runner.Answered(*late, error);
  r.runner.Answered(*job, grpc::Status::OK);
  EXPECT_EQ(r.runner.inflight(), 0);
}

}  // namespace
}  // namespace dot::server
