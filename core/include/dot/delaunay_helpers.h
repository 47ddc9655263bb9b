// SPDX-License-Identifier: AGPL-3.0-or-later
// TetGen, and fairing's sparse solves, in helper processes. TetGen is
// neither thread-safe (file-scope predicate state) nor crash-safe (it aborts
// or segfaults on some inputs), and neither it nor a sparse LU can be
// interrupted, so each runs in a child process of its own from a small pool:
// concurrent requests never share TetGen state, a crash fails only the
// request that caused it, a cancel or deadline kills the child at once, and
// each child is memory-capped with setrlimit. Dead children are restarted
// on demand.
//
// Pipe protocol (host byte order): every request starts with uint32 kind
// (HelperRequest) and uint64 memory budget (bytes the helper may grow by for
// this request; 0: its own cap only); every reply with int32 status code,
// uint32 message length, message bytes and uint64 count (0 unless OK).
//   kTetrahedralize: uint64 n, n * 3 doubles ->
//                    count * 4 int32 corners, count * 4 int32 neighbours
//   kSolveSparse:    uint64 n, uint64 nonzeros, int32 rhs, nonzeros int32
//                    rows, nonzeros int32 columns, nonzeros doubles,
//                    n * rhs doubles (B, column-major) ->
//                    count = n * rhs doubles (X, column-major)
#ifndef DOT_DELAUNAY_HELPERS_H_
#define DOT_DELAUNAY_HELPERS_H_

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "dot/control.h"

namespace dot {

// AddressSanitizer reserves terabytes of shadow address space, so an
// RLIMIT_AS cap would make its every mmap fail: sanitizer builds run the
// helpers uncapped.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kCanCapAddressSpace = false;
#else
inline constexpr bool kCanCapAddressSpace = true;
#endif

enum class HelperRequest : uint32_t { kTetrahedralize = 1, kSolveSparse = 2 };

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
  // How a user raises that limit, for out-of-memory messages (the server
  // sets its flag); empty: not named.
  std::string memory_limit_setting;
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
  // SolveSparseLu in a helper, on the same terms.
  Status SolveSparse(const SparseSystem& system, std::vector<double>* x,
                     const std::atomic<bool>* cancel,
                     std::chrono::steady_clock::time_point deadline,
                     int64_t memory_budget_bytes = 0);
  int64_t starts() const { return starts_; }  // helper processes started
  std::vector<int> Pids() const;              // running helpers, for tests

 private:
  struct Helper {
    int pid = -1;  // a pid_t (static_assert in the .cc): no POSIX header here
    int to_child = -1, from_child = -1;
    bool busy = false;
  };
  Status Spawn(Helper* h);
  int Kill(Helper* h);  // returns the wait status
  // True (with the wait status) when the helper has ended by itself; it is
  // then cleaned up, ready to be spawned again.
  bool Reap(Helper* h, int* status);
  // One request to a free helper: `send` writes its body, `receive` reads
  // the `count` items of `item_bytes` each of an answer (through `read`,
  // which kills the helper on cancel or deadline). `what` names the work in
  // messages.
  using ReadFn = std::function<Status(void* data, size_t len)>;
  using SendFn = std::function<bool(int fd)>;
  using ReceiveFn = std::function<Status(uint64_t count, const ReadFn& read)>;
  Status Call(HelperRequest kind, const std::string& what, size_t item_bytes,
              const SendFn& send, const ReceiveFn& receive,
              const std::atomic<bool>* cancel,
              std::chrono::steady_clock::time_point deadline,
              int64_t memory_budget_bytes);
  Status Exchange(Helper* h, HelperRequest kind, const std::string& what,
                  size_t item_bytes, const SendFn& send,
                  const ReceiveFn& receive, const std::atomic<bool>* cancel,
                  std::chrono::steady_clock::time_point deadline,
                  int64_t memory_budget_bytes);

  const DelaunayHelperOptions config_;
  mutable std::mutex mu_;
  std::condition_variable free_;
  std::vector<Helper> helpers_;
  std::atomic<int64_t> starts_{0};
};

// The helper process's main loop: serve requests from `in_fd` until EOF
// (in a build without TetGen, tetrahedralizations are answered
// kInvalidArgument).
int RunDelaunayHelper(int in_fd, int out_fd);

// A helper program's main: caps its address space as its arguments say
// ([--memory-limit-bytes N]), then serves stdin/stdout. `program` names it
// in the usage message.
int DelaunayHelperMain(const char* program, int argc, char** argv);

}  // namespace dot

#endif  // DOT_DELAUNAY_HELPERS_H_
