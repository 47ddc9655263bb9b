// SPDX-License-Identifier: AGPL-3.0-or-later
#include "compute/compute_pool.h"

namespace dot::server {

ComputePool::ComputePool(const ComputePoolOptions& options)
    : threads_(options.threads), capacity_(options.queue_size) {
  for (int i = 0; i < options.threads; ++i) {
    workers_.emplace_back([this] { Work(); });
  }
}

ComputePool::~ComputePool() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
  }
  cv_.notify_all();
  for (std::thread& t : workers_) t.join();
}

bool ComputePool::TrySubmit(std::function<void()> task, Lane lane) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_ ||
        static_cast<int>(small_.size() + large_.size()) >= capacity_) {
      return false;
    }
    (lane == Lane::kSmall ? small_ : large_).push_back(std::move(task));
  }
  cv_.notify_all();  // a worker free for this lane may not be the next one
  return true;
}

bool ComputePool::Runnable() const {
  if (busy_ >= threads()) return false;
  return !small_.empty() || (!large_.empty() && busy_large_ < LargeSlots());
}

bool ComputePool::TryRunHere(const std::function<void()>& task) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_ || !small_.empty() || busy_ >= threads()) return false;
    ++busy_;
  }
  // The slot is given back however the task ends.
  struct Release {
    ComputePool* pool;
    ~Release() {
      {
        std::lock_guard<std::mutex> lock(pool->mu_);
        --pool->busy_;
      }
      pool->cv_.notify_all();  // the slot may be what a queued task waits for
    }
  } release{this};
  task();
  return true;
}

int ComputePool::queued() const {
  std::lock_guard<std::mutex> lock(mu_);
  return static_cast<int>(small_.size() + large_.size());
}

int ComputePool::busy() const {
  std::lock_guard<std::mutex> lock(mu_);
  return busy_;
}

void ComputePool::Work() {
  for (;;) {
    std::function<void()> task;
    bool large = false;
    {
      std::unique_lock<std::mutex> lock(mu_);
      // Queued work runs within the slot bound even while stopping.
      cv_.wait(lock, [this] {
        return Runnable() || (stopping_ && small_.empty() && large_.empty());
      });
      if (small_.empty() && large_.empty()) return;  // stopping and drained
      large = small_.empty();
      std::deque<std::function<void()>>& queue = large ? large_ : small_;
      task = std::move(queue.front());
      queue.pop_front();
      ++busy_;
      busy_large_ += large;
    }
    task();
    {
      std::lock_guard<std::mutex> lock(mu_);
      --busy_;
      busy_large_ -= large;
    }
    cv_.notify_all();
  }
}

}  // namespace dot::server
