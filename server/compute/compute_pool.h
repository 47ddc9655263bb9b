// SPDX-License-Identifier: AGPL-3.0-or-later
// Fixed-size thread pool with a bounded queue: TrySubmit refuses work when
// the queue is full, so overload is answered at once instead of queued
// without bound. `threads` is also the number of compute slots: a caller may
// run a task on its own thread in a free slot (TryRunHere), which saves two
// thread handoffs for small tasks without exceeding the bound.
//
// Two lanes: small tasks (polygons) are taken before large ones (mesh
// fills, very large polygons), and large tasks never hold more than
// threads - 1 slots, so a few slow fills cannot keep a 20-vertex Triangulate
// waiting (with one thread, a large task still takes the only slot).
#ifndef DOT_SERVER_COMPUTE_POOL_H_
#define DOT_SERVER_COMPUTE_POOL_H_

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace dot::server {

enum class Lane { kSmall, kLarge };

struct ComputePoolOptions {
  int threads = 0;      // compute threads; 0: one per core
  int queue_size = 64;  // tasks that may wait for a thread
};

class ComputePool {
 public:
  // `options.threads` must be resolved (> 0) by the caller.
  explicit ComputePool(const ComputePoolOptions& options);
  ~ComputePool();  // runs what is queued, then joins
  ComputePool(const ComputePool&) = delete;
  ComputePool& operator=(const ComputePool&) = delete;

  // False when `queue_capacity` tasks are already waiting.
  bool TrySubmit(std::function<void()> task, Lane lane = Lane::kSmall);
  // Runs `task` on the calling thread when a slot is free and nothing is
  // queued (so it cannot overtake waiting work); false otherwise.
  bool TryRunHere(const std::function<void()>& task);
  int queued() const;
  int busy() const;
  int threads() const { return threads_; }
  int capacity() const { return capacity_; }

 private:
  void Work();
  int LargeSlots() const { return std::max(1, threads() - 1); }
  bool Runnable() const;  // under mu_: a queued task may start now
  const int threads_;     // not workers_.size(): workers read it as they start
  const int capacity_;
  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> small_, large_;
  int busy_ = 0;        // slots in use, by workers or TryRunHere callers
  int busy_large_ = 0;  // of which by large tasks
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_COMPUTE_POOL_H_
