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
  EXPECT_EQ(w.WriteDone(true, nullptr), AnswerWriter::Next::kNothing)
      << "the job still runs";
  EXPECT_FALSE(w.ClaimProgress(kHour)) << "younger than the interval";
  EXPECT_TRUE(w.ClaimProgress(kHour, /*force=*/true));
}

TEST(AnswerWriterTest, TheJobsEndHandsTheAnswerToAWriteInFlight) {
  AnswerWriter w;
  ASSERT_TRUE(w.ClaimProgress(kHour));
  EXPECT_FALSE(w.JobDone()) << "the write in flight hands it over";
  EXPECT_EQ(w.WriteDone(true, nullptr), AnswerWriter::Next::kAnswer)
      << "now the answer";
  EXPECT_FALSE(w.ClaimProgress(kHour, true)) << "no progress after the job";
}

TEST(AnswerWriterTest, WithNoWriteInFlightTheJobsEndWritesTheAnswer) {
  AnswerWriter w;
  EXPECT_TRUE(w.JobDone());
  EXPECT_EQ(w.WriteDone(true, nullptr), AnswerWriter::Next::kAnswer)
      << "each answer message in turn";
}

TEST(AnswerWriterTest, AFailedWriteStopsTheJobAsClientGone) {
  AnswerWriter w;
  Job job;
  ASSERT_TRUE(w.ClaimProgress(kHour));
  EXPECT_EQ(w.WriteDone(false, &job), AnswerWriter::Next::kNothing);
  EXPECT_TRUE(w.broken());
  EXPECT_TRUE(job.cancel);
  EXPECT_EQ(job.stop, StopReason::kClientGone);
}

TEST(AnswerWriterTest, AForcedReportThatFindsAWriteInFlightGoesAfterIt) {
  AnswerWriter w;
  int kept = 0, taken = 0;
  ASSERT_TRUE(w.ClaimProgress(kHour));
  EXPECT_FALSE(w.ClaimProgress(kHour, false, [&] { ++kept; }))
      << "not forced: skipped, not kept";
  EXPECT_EQ(kept, 0);
  EXPECT_FALSE(w.ClaimProgress(kHour, true, [&] { kept = 1; }));
  EXPECT_FALSE(w.ClaimProgress(kHour, true, [&] { kept = 2; }))
      << "a newer forced report replaces the kept one";
  EXPECT_EQ(kept, 2);
  EXPECT_EQ(w.WriteDone(true, nullptr, [&] { ++taken; }),
            AnswerWriter::Next::kKept);
  EXPECT_EQ(taken, 1);
  EXPECT_FALSE(w.ClaimProgress(kHour, false)) << "the kept one is in flight";
  EXPECT_EQ(w.WriteDone(true, nullptr), AnswerWriter::Next::kNothing);
  // Kept when the job ends: the kept report goes first, then the answer.
  ASSERT_TRUE(w.ClaimProgress(kHour, true));
  EXPECT_FALSE(w.ClaimProgress(kHour, true, [] {}));
  EXPECT_FALSE(w.JobDone());
  EXPECT_EQ(w.WriteDone(true, nullptr, [] {}), AnswerWriter::Next::kKept);
  EXPECT_EQ(w.WriteDone(true, nullptr), AnswerWriter::Next::kAnswer);
}

TEST(AnswerWriterTest, AKeptReportIsDroppedWhenTheWriteFails) {
  AnswerWriter w;
  Job job;
  ASSERT_TRUE(w.ClaimProgress(kHour));
  EXPECT_FALSE(w.ClaimProgress(kHour, true, [] {}));
  EXPECT_FALSE(w.JobDone());
  EXPECT_EQ(w.WriteDone(false, &job), AnswerWriter::Next::kAnswer)
      << "the holder finishes (broken)";
  EXPECT_TRUE(w.broken());
}

TEST(AnswerWriterTest, NoProgressOnceTheCallIsClosed) {
  AnswerWriter w;
  w.Close();
  EXPECT_FALSE(w.ClaimProgress(kHour, true));
}

}  // namespace
}  // namespace dot::server
