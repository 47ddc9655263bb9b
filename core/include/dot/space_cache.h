// SPDX-License-Identifier: AGPL-3.0-or-later
// A bounded, thread-safe cache of prepared search spaces: the Delaunay
// candidates and adjacency of recent polygons, which do not depend on the
// metric weights. Re-solving the same polygon (same coordinates, normals and
// search-space options) with new weights, as a user dragging a weight slider
// does, then runs only the dynamic program. Pass one through
// Control::space_cache; Result::stats.cache_hit says whether it served.
// Keys are the exact input bytes, so a hit is never a hash collision. Least
// recently used entries are evicted once the entries exceed `max_bytes`.
#ifndef DOT_SPACE_CACHE_H_
#define DOT_SPACE_CACHE_H_

#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>

namespace dot {

struct PreparedSpace;  // defined inside the library

class SpaceCache {
 public:
  explicit SpaceCache(int64_t max_bytes) : max_bytes_(max_bytes) {}
  SpaceCache(const SpaceCache&) = delete;
  SpaceCache& operator=(const SpaceCache&) = delete;

  struct Counters {
    int64_t hits = 0, misses = 0, evictions = 0, entries = 0, bytes = 0;
  };
  Counters counters() const;
  int64_t max_bytes() const { return max_bytes_; }

  // Used by Triangulate. Find returns null on a miss; Insert ignores spaces
  // larger than the whole cache.
  std::shared_ptr<const PreparedSpace> Find(const std::string& key);
  void Insert(const std::string& key,
              std::shared_ptr<const PreparedSpace> space, int64_t bytes);

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const PreparedSpace> space;
    int64_t bytes;
  };
  const int64_t max_bytes_;
  mutable std::mutex mu_;
  std::list<Entry> lru_;  // most recently used first
  std::unordered_map<std::string_view, std::list<Entry>::iterator> index_;
  Counters counters_;
};

}  // namespace dot

#endif  // DOT_SPACE_CACHE_H_
