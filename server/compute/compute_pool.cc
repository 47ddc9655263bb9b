// SPDX-License-Identifier: AGPL-3.0-or-later
#include "compute/compute_pool.h"

namespace dot::server {

ComputePool::ComputePool(const ComputePoolOptions& options)
    : capacity_(options.queue_size) {
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

bool ComputePool::TrySubmit(std::function<void()> task) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_ || static_cast<int>(queue_.size()) >= capacity_) return false;
    queue_.push_back(std::move(task));
  }
  cv_.notify_one();
  return true;
}

bool ComputePool::TryRunHere(const std::function<void()>& task) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_ || !queue_.empty() || busy_ >= threads()) return false;
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
      pool->cv_.notify_one();  // the slot may be what a queued task waits for
    }
  } release{this};
  task();
  return true;
}

int ComputePool::queued() const {
  std::lock_guard<std::mutex> lock(mu_);
  return static_cast<int>(queue_.size());
}

int ComputePool::busy() const {
  std::lock_guard<std::mutex> lock(mu_);
  return busy_;
}

void ComputePool::Work() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock<std::mutex> lock(mu_);
      // Queued work runs within the slot bound even while stopping.
      cv_.wait(lock, [this] {
        return (!queue_.empty() && busy_ < threads()) ||
               (stopping_ && queue_.empty());
      });
      if (queue_.empty()) return;  // stopping and drained
      task = std::move(queue_.front());
      queue_.pop_front();
      ++busy_;
    }
    task();
    {
      std::lock_guard<std::mutex> lock(mu_);
      --busy_;
    }
    cv_.notify_one();
  }
}

}  // namespace dot::server
