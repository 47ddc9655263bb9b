// SPDX-License-Identifier: AGPL-3.0-or-later
// The compute pool's lanes: large tasks never take every slot, and small
// tasks go first.
#include "compute/compute_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace dot::server {
namespace {

TEST(ComputePoolTest, LargeTasksLeaveASlotForSmallOnes) {
  // Before: two slow fills held both slots and a 20-vertex Triangulate
  // waited behind them until its deadline.
  ComputePool pool({/*threads=*/2, /*queue_size=*/16});
  std::promise<void> release;
  std::shared_future<void> gate = release.get_future().share();
  std::atomic<int> large_started{0};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(pool.TrySubmit(
        [&, gate] {
          ++large_started;
          gate.wait();
        },
        Lane::kLarge));
  }
  std::promise<void> small_ran;
  ASSERT_TRUE(pool.TrySubmit([&] { small_ran.set_value(); }, Lane::kSmall));
  // Liveness, not timing: the small task runs while every large one waits.
  EXPECT_EQ(small_ran.get_future().wait_for(std::chrono::seconds(60)),
            std::future_status::ready);
  // One large task takes the other slot (small ones go first, so it may
  // start after the small one ran); a second never does while it holds it.
  for (int i = 0; i < 60000 && large_started.load() == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(large_started.load(), 1);  // threads - 1 slots for large tasks
  release.set_value();
}

TEST(ComputePoolTest, SmallTasksAreTakenBeforeQueuedLargeOnes) {
  ComputePool pool({/*threads=*/1, /*queue_size=*/16});
  std::promise<void> release;
  std::shared_future<void> gate = release.get_future().share();
  ASSERT_TRUE(pool.TrySubmit([gate] { gate.wait(); }, Lane::kSmall));
  std::vector<char> order;
  std::mutex mu;
  std::promise<void> all_done;
  auto record = [&](char c) {
    std::lock_guard<std::mutex> lock(mu);
    order.push_back(c);
    if (order.size() == 3) all_done.set_value();
  };
  ASSERT_TRUE(pool.TrySubmit([&] { record('L'); }, Lane::kLarge));
  ASSERT_TRUE(pool.TrySubmit([&] { record('s'); }, Lane::kSmall));
  ASSERT_TRUE(pool.TrySubmit([&] { record('t'); }, Lane::kSmall));
  release.set_value();
  ASSERT_EQ(all_done.get_future().wait_for(std::chrono::seconds(60)),
            std::future_status::ready);
  EXPECT_EQ(std::string(order.begin(), order.end()), "stL");
}

}  // namespace
}  // namespace dot::server
