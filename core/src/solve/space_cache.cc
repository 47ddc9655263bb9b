// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/space_cache.h"

namespace dot {

SpaceCache::Counters SpaceCache::counters() const {
  std::lock_guard<std::mutex> lock(mu_);
  return counters_;
}

std::shared_ptr<const PreparedSpace> SpaceCache::Find(const std::string& key) {
  std::lock_guard<std::mutex> lock(mu_);
  const auto it = index_.find(key);
  if (it == index_.end()) {
    ++counters_.misses;
    return nullptr;
  }
  ++counters_.hits;
  lru_.splice(lru_.begin(), lru_, it->second);
  return it->second->space;
}

void SpaceCache::Insert(const std::string& key,
                        std::shared_ptr<const PreparedSpace> space,
                        int64_t bytes) {
  bytes += static_cast<int64_t>(key.size());
  if (bytes > max_bytes_) return;
  std::lock_guard<std::mutex> lock(mu_);
  if (index_.count(key) != 0) return;  // a concurrent miss got there first
  while (!lru_.empty() && counters_.bytes + bytes > max_bytes_) {
    counters_.bytes -= lru_.back().bytes;
    index_.erase(lru_.back().key);
    lru_.pop_back();
    ++counters_.evictions;
  }
  lru_.push_front({key, std::move(space), bytes});
  index_.emplace(lru_.front().key, lru_.begin());
  counters_.bytes += bytes;
  counters_.entries = static_cast<int64_t>(lru_.size());
}

}  // namespace dot
