// SPDX-License-Identifier: AGPL-3.0-or-later
// TetGen in helper processes. TetGen is neither thread-safe (file-scope
// predicate state) nor crash-safe (it aborts or segfaults on some inputs),
// so each tetrahedralization runs in a child process of its own from a small
// pool: concurrent requests never share TetGen state, a crash fails only the
// request that caused it, a cancel kills the child at once, and each child
// is memory-capped with setrlimit. Dead children are restarted on demand.
//
// Pipe protocol (host byte order):
//   request:  uint64 memory budget (bytes the helper may grow by for this
//             request; 0: its own cap only), uint64 n, then n * 3 doubles
//   response: int32 status code, uint32 message length, message bytes,
//             uint64 t, then t * 4 int32 corners and t * 4 int32 neighbours
#ifndef DOT_DELAUNAY_HELPERS_H_
#define DOT_DELAUNAY_HELPERS_H_

#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "dot/triangulate.h"

namespace dot {

// AddressSanitizer reserves terabytes of shadow address space, so an
// RLIMIT_AS cap would make its every mmap fail: sanitizer builds run the
// helpers uncapped.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kCanCapAddressSpace = false;
#else
inline constexpr bool kCanCapAddressSpace = true;
#endif

struct DelaunayHelperOptions {
  // Helper processes; -1: one per compute thread, 0: TetGen in-process
  // (serialized) instead.
  int count = -1;
  // The helper binary (dot-delaunay-helper, or any program whose main
  // calls DelaunayHelperMain); empty: next to the running binary.
  std::string executable;
  // Arguments before --memory-limit-bytes (a program that is also its own
  // helper, such as dotctl, selects the helper mode with one).
  std::vector<std::string> arguments;
  // Address-space limit of each helper (setrlimit).
  int64_t memory_limit_bytes = int64_t{4} << 30;
};

class DelaunayHelperPool {
 public:
  // `options` resolved: count > 0, executable set.
  explicit DelaunayHelperPool(DelaunayHelperOptions options);
  ~DelaunayHelperPool();  // kills the helpers
  DelaunayHelperPool(const DelaunayHelperPool&) = delete;
  DelaunayHelperPool& operator=(const DelaunayHelperPool&) = delete;

  // Blocks for a free helper; kCancelled / kDeadlineExceeded kill it. With
  // `memory_budget_bytes` > 0 the helper may grow by at most that much for
  // this request (it lowers its soft RLIMIT_AS to its size plus the budget,
  // then restores it), and a reply larger than the budget is refused
  // unread: a request's budget bounds TetGen as it bounds CGAL.
  Status Tetrahedralize(const std::vector<Vec3>& points,
                        Tetrahedralization* out,
                        const std::atomic<bool>* cancel,
                        std::chrono::steady_clock::time_point deadline,
                        int64_t memory_budget_bytes = 0);
  int64_t starts() const { return starts_; }  // helper processes started
  std::vector<pid_t> Pids() const;            // running helpers, for tests

 private:
  struct Helper {
    pid_t pid = -1;
    int to_child = -1, from_child = -1;
    bool busy = false;
  };
  Status Spawn(Helper* h);
  int Kill(Helper* h);  // returns the wait status
  // True (with the wait status) when the helper has ended by itself; it is
  // then cleaned up, ready to be spawned again.
  bool Reap(Helper* h, int* status);
  Status Exchange(Helper* h, const std::vector<Vec3>& points,
                  int64_t memory_budget_bytes, Tetrahedralization* out,
                  const std::atomic<bool>* cancel,
                  std::chrono::steady_clock::time_point deadline);

  const DelaunayHelperOptions config_;
  mutable std::mutex mu_;
  std::condition_variable free_;
  std::vector<Helper> helpers_;
  std::atomic<int64_t> starts_{0};
};

// The helper process's main loop: serve requests from `in_fd` until EOF
// (in a build without TetGen, each answered kInvalidArgument).
int RunDelaunayHelper(int in_fd, int out_fd);

// A helper program's main: caps its address space as its arguments say
// ([--memory-limit-bytes N]), then serves stdin/stdout. `program` names it
// in the usage message.
int DelaunayHelperMain(const char* program, int argc, char** argv);

}  // namespace dot

#endif  // DOT_DELAUNAY_HELPERS_H_
