// SPDX-License-Identifier: AGPL-3.0-or-later
// AnswerWriter, the write decisions of a "progress, then the answer"
// stream, without a socket: one write in flight, progress at most once per
// interval and never after the job, the answer written by whoever holds
// the right when the job ends, and a failed write stopping the job.
#include "rpc/answer_writer.h"

#include <gtest/gtest.h>

#include <chrono>

namespace dot::server {
namespace {

constexpr auto kHour = std::chrono::hours(1);

TEST(AnswerWriterTest, OneProgressWriteAtATimeAndAtMostOncePerInterval) {
  AnswerWriter w;
  EXPECT_TRUE(w.ClaimProgress(kHour));
  EXPECT_FALSE(w.ClaimProgress(kHour, /*force=*/true)) << "one in flight";
  EXPECT_FALSE(w.WriteDone(true, nullptr)) << "the job still runs";
  EXPECT_FALSE(w.ClaimProgress(kHour)) << "younger than the interval";
  EXPECT_TRUE(w.ClaimProgress(kHour, /*force=*/true));
}

TEST(AnswerWriterTest, TheJobsEndHandsTheAnswerToAWriteInFlight) {
  AnswerWriter w;
  ASSERT_TRUE(w.ClaimProgress(kHour));
  EXPECT_FALSE(w.JobDone()) << "the write in flight hands it over";
  EXPECT_TRUE(w.WriteDone(true, nullptr)) << "now the answer";
  EXPECT_FALSE(w.ClaimProgress(kHour, true)) << "no progress after the job";
}

TEST(AnswerWriterTest, WithNoWriteInFlightTheJobsEndWritesTheAnswer) {
  AnswerWriter w;
  EXPECT_TRUE(w.JobDone());
  EXPECT_TRUE(w.WriteDone(true, nullptr)) << "each answer message in turn";
}

TEST(AnswerWriterTest, AFailedWriteStopsTheJobAsClientGone) {
  AnswerWriter w;
  Job job;
  ASSERT_TRUE(w.ClaimProgress(kHour));
  EXPECT_FALSE(w.WriteDone(false, &job));
  EXPECT_TRUE(w.broken());
  EXPECT_TRUE(job.cancel);
  EXPECT_EQ(job.stop, StopReason::kClientGone);
}

TEST(AnswerWriterTest, NoProgressOnceTheCallIsClosed) {
  AnswerWriter w;
  w.Close();
  EXPECT_FALSE(w.ClaimProgress(kHour, true));
}

}  // namespace
}  // namespace dot::server
