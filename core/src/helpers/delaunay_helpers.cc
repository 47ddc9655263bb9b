// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/delaunay_helpers.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <new>
#include <type_traits>

extern char** environ;

namespace dot {
namespace {

using Clock = std::chrono::steady_clock;

Status Internal(std::string m) {
  return MakeStatus(StatusCode::kInternal, std::move(m));
}

bool WriteAll(int fd, const void* data, size_t len) {
  const char* p = static_cast<const char*>(data);
  while (len > 0) {
    const ssize_t w = ::write(fd, p, len);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    len -= static_cast<size_t>(w);
  }
  return true;
}

// Blocking read of exactly `len` bytes (helper side).
bool ReadAll(int fd, void* data, size_t len) {
  char* p = static_cast<char*>(data);
  while (len > 0) {
    const ssize_t r = ::read(fd, p, len);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r;
    len -= static_cast<size_t>(r);
  }
  return true;
}

}  // namespace

namespace {

// While alive, this process may grow by at most `bytes` of address space
// (the soft RLIMIT_AS, below the hard cap set at start); then restored.
class GrowthLimit {
 public:
  explicit GrowthLimit(uint64_t bytes) {
    if (!kCanCapAddressSpace || bytes == 0 ||
        ::getrlimit(RLIMIT_AS, &saved_) != 0) {
      return;
    }
    std::ifstream status("/proc/self/status");
    std::string line;
    uint64_t vm_kib = 0;
    while (std::getline(status, line)) {
      if (line.rfind("VmSize:", 0) == 0) vm_kib = std::atoll(line.c_str() + 7);
    }
    const rlimit limit{std::min<rlim_t>(saved_.rlim_max, vm_kib * 1024 + bytes),
                       saved_.rlim_max};
    active_ = ::setrlimit(RLIMIT_AS, &limit) == 0;
  }
  ~GrowthLimit() {
    if (active_) ::setrlimit(RLIMIT_AS, &saved_);
  }

 private:
  rlimit saved_{};
  bool active_ = false;
};

}  // namespace

namespace {

// Writes a reply: status, then `count` items of `item_bytes` from each of
// `arrays` in turn (nothing when the status is not OK).
bool WriteReply(int fd, const Status& s, uint64_t count,
                std::initializer_list<std::pair<const void*, size_t>> arrays) {
  const int32_t code = static_cast<int32_t>(s.code);
  const auto len = static_cast<uint32_t>(s.message.size());
  if (!s.ok()) count = 0;
  if (!WriteAll(fd, &code, sizeof code) || !WriteAll(fd, &len, sizeof len) ||
      !WriteAll(fd, s.message.data(), len) ||
      !WriteAll(fd, &count, sizeof count)) {
    return false;
  }
  for (const auto& [data, item_bytes] : arrays) {
    if (!WriteAll(fd, data, count * item_bytes)) return false;
  }
  return true;
}

// The helper's exit code when it cannot hold a request's input: it ends,
// since the rest of the request is unread (the server reports it).
constexpr int kExitInputOutOfMemory = 3;

Status OutOfMemory(const std::string& what) {
  return MakeStatus(StatusCode::kResourceExhausted,
                    what + " ran out of memory");
}

bool ServeTetrahedralize(int in_fd, int out_fd, uint64_t budget) {
  uint64_t n = 0;
  if (!ReadAll(in_fd, &n, sizeof n)) return false;
  // The input is held before the request's budget applies (the budget is
  // for the work); only the helper's own cap can refuse it.
  std::vector<Vec3> points;
  try {
    points.resize(n);
  } catch (const std::bad_alloc&) {
    std::_Exit(kExitInputOutOfMemory);  // the request is unread: end
  }
  if (!ReadAll(in_fd, points.data(), n * sizeof(Vec3))) return false;
  Tetrahedralization t;
  Status s;
  {
    const GrowthLimit limit(budget);
    try {
      s = TetgenTetrahedralize(points, &t);
    } catch (const std::bad_alloc&) {  // copying TetGen's output
      t = {};
      s = OutOfMemory("the Delaunay step on " + std::to_string(n) + " points");
    }
  }
  return WriteReply(out_fd, s, t.tets.size(),
                    {{t.tets.data(), sizeof(t.tets[0])},
                     {t.neighbors.data(), sizeof(t.neighbors[0])}});
}

bool ServeSolveSparse(int in_fd, int out_fd, uint64_t budget) {
  uint64_t n = 0, nonzeros = 0;
  int32_t rhs = 0;
  if (!ReadAll(in_fd, &n, sizeof n) ||
      !ReadAll(in_fd, &nonzeros, sizeof nonzeros) ||
      !ReadAll(in_fd, &rhs, sizeof rhs) || rhs < 0) {
    return false;
  }
  std::vector<double> x;
  Status s;
  SparseSystem system;
  system.n = static_cast<int64_t>(n);
  system.rhs = rhs;
  try {
    system.rows.resize(nonzeros);
    system.cols.resize(nonzeros);
    system.values.resize(nonzeros);
    system.b.resize(n * static_cast<uint64_t>(rhs));
  } catch (const std::bad_alloc&) {
    std::_Exit(kExitInputOutOfMemory);  // the request is unread: end
  }
  if (!ReadAll(in_fd, system.rows.data(), nonzeros * sizeof(int32_t)) ||
      !ReadAll(in_fd, system.cols.data(), nonzeros * sizeof(int32_t)) ||
      !ReadAll(in_fd, system.values.data(), nonzeros * sizeof(double)) ||
      !ReadAll(in_fd, system.b.data(), system.b.size() * sizeof(double))) {
    return false;
  }
  const GrowthLimit limit(budget);  // after the input, as above
  try {
    s = SolveSparseLu(system, &x);
  } catch (const std::bad_alloc&) {
    x = {};
    s = OutOfMemory("the sparse solve of " + std::to_string(n) + " unknowns");
  }
  return WriteReply(out_fd, s, x.size(), {{x.data(), sizeof(double)}});
}

}  // namespace

int RunDelaunayHelper(int in_fd, int out_fd) {
  for (;;) {
    uint32_t kind = 0;
    uint64_t budget = 0;
    if (!ReadAll(in_fd, &kind, sizeof kind)) return 0;  // server closed
    if (!ReadAll(in_fd, &budget, sizeof budget)) return 1;
    bool ok = false;
    switch (static_cast<HelperRequest>(kind)) {
      case HelperRequest::kTetrahedralize:
        ok = ServeTetrahedralize(in_fd, out_fd, budget);
        break;
      case HelperRequest::kSolveSparse:
        ok = ServeSolveSparse(in_fd, out_fd, budget);
        break;
    }
    if (!ok) return 1;
  }
}

int DelaunayHelperMain(const char* program, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--memory-limit-bytes") == 0 && i + 1 < argc) {
      const rlim_t limit = std::strtoull(argv[++i], nullptr, 10);
      const rlimit rl{limit, limit};
      if (kCanCapAddressSpace && limit > 0 && setrlimit(RLIMIT_AS, &rl) != 0) {
        std::cerr << program << ": setrlimit failed\n";
        return 2;
      }
    } else {
      std::cerr << "usage: " << program
                << " [--memory-limit-bytes N]\n"
                   "Started by dot-server or dotctl; speaks a binary protocol "
                   "on stdin/stdout.\n";
      return 2;
    }
  }
  return RunDelaunayHelper(STDIN_FILENO, STDOUT_FILENO);
}

DelaunayHelperPool::DelaunayHelperPool(DelaunayHelperOptions options)
    : config_(std::move(options)), helpers_(std::max(1, config_.count)) {
  // A helper that dies mid-request must surface as EPIPE, not kill us.
  ::signal(SIGPIPE, SIG_IGN);
}

DelaunayHelperPool::~DelaunayHelperPool() {
  std::lock_guard<std::mutex> lock(mu_);
  for (Helper& h : helpers_) Kill(&h);
}

static_assert(std::is_same_v<pid_t, int>, "Helper::pid holds a pid_t");

std::vector<int> DelaunayHelperPool::Pids() const {
  std::lock_guard<std::mutex> lock(mu_);
  std::vector<int> pids;
  for (const Helper& h : helpers_) {
    if (h.pid > 0) pids.push_back(h.pid);
  }
  return pids;
}

Status DelaunayHelperPool::Spawn(Helper* h) {
  int to[2], from[2];
  if (::pipe2(to, O_CLOEXEC) != 0) return Internal("pipe failed");
  if (::pipe2(from, O_CLOEXEC) != 0) {
    ::close(to[0]);
    ::close(to[1]);
    return Internal("pipe failed");
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, to[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, from[1], STDOUT_FILENO);
  const std::string limit = std::to_string(config_.memory_limit_bytes);
  std::vector<char*> argv = {const_cast<char*>(config_.executable.c_str())};
  for (const std::string& a : config_.arguments) {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.insert(argv.end(), {const_cast<char*>("--memory-limit-bytes"),
                           const_cast<char*>(limit.c_str()), nullptr});
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, config_.executable.c_str(), &actions,
                               nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(to[0]);
  ::close(from[1]);
  if (rc != 0) {
    ::close(to[1]);
    ::close(from[0]);
    return Internal("cannot start Delaunay helper '" + config_.executable +
                    "': " + std::strerror(rc));
  }
  h->pid = pid;
  h->to_child = to[1];
  h->from_child = from[0];
  return OkStatus();
}

bool DelaunayHelperPool::Reap(Helper* h, int* status) {
  if (h->pid <= 0 || ::waitpid(h->pid, status, WNOHANG) != h->pid) {
    return false;
  }
  h->pid = -1;
  Kill(h);  // closes the pipes
  return true;
}

int DelaunayHelperPool::Kill(Helper* h) {
  int status = 0;
  if (h->pid > 0) {
    ::kill(h->pid, SIGKILL);
    ::waitpid(h->pid, &status, 0);
  }
  if (h->to_child >= 0) ::close(h->to_child);
  if (h->from_child >= 0) ::close(h->from_child);
  h->pid = -1;
  h->to_child = h->from_child = -1;
  return status;
}

Status DelaunayHelperPool::Tetrahedralize(const std::vector<Vec3>& points,
                                          Tetrahedralization* out,
                                          const std::atomic<bool>* cancel,
                                          Clock::time_point deadline,
                                          int64_t memory_budget_bytes) {
  const uint64_t n = points.size();
  auto send = [&](int fd) {
    return WriteAll(fd, &n, sizeof n) &&
           WriteAll(fd, points.data(), n * sizeof(Vec3));
  };
  auto receive = [&](uint64_t count, const ReadFn& read) -> Status {
    out->tets.resize(count);
    out->neighbors.resize(count);
    Status s = read(out->tets.data(), count * sizeof(out->tets[0]));
    if (s.ok()) {
      s = read(out->neighbors.data(), count * sizeof(out->neighbors[0]));
    }
    return s;
  };
  return Call(HelperRequest::kTetrahedralize, "the Delaunay step",
              sizeof(out->tets[0]) + sizeof(out->neighbors[0]), send, receive,
              cancel, deadline, memory_budget_bytes);
}

Status DelaunayHelperPool::SolveSparse(const SparseSystem& system,
                                       std::vector<double>* x,
                                       const std::atomic<bool>* cancel,
                                       Clock::time_point deadline,
                                       int64_t memory_budget_bytes) {
  const auto n = static_cast<uint64_t>(system.n);
  const uint64_t nonzeros = system.values.size();
  if (system.rows.size() != nonzeros || system.cols.size() != nonzeros ||
      system.b.size() != n * static_cast<uint64_t>(system.rhs)) {
    return InvalidArgument("malformed sparse system");
  }
  auto send = [&](int fd) {
    return WriteAll(fd, &n, sizeof n) &&
           WriteAll(fd, &nonzeros, sizeof nonzeros) &&
           WriteAll(fd, &system.rhs, sizeof system.rhs) &&
           WriteAll(fd, system.rows.data(), nonzeros * sizeof(int32_t)) &&
           WriteAll(fd, system.cols.data(), nonzeros * sizeof(int32_t)) &&
           WriteAll(fd, system.values.data(), nonzeros * sizeof(double)) &&
           WriteAll(fd, system.b.data(), system.b.size() * sizeof(double));
  };
  auto receive = [&](uint64_t count, const ReadFn& read) -> Status {
    if (count != system.b.size()) {
      return Internal("the helper answered " + std::to_string(count) +
                      " values for a solution of " +
                      std::to_string(system.b.size()));
    }
    x->resize(count);
    return read(x->data(), count * sizeof(double));
  };
  return Call(HelperRequest::kSolveSparse, "the sparse solve", sizeof(double),
              send, receive, cancel, deadline, memory_budget_bytes);
}

Status DelaunayHelperPool::Call(HelperRequest kind, const std::string& what,
                                size_t item_bytes, const SendFn& send,
                                const ReceiveFn& receive,
                                const std::atomic<bool>* cancel,
                                Clock::time_point deadline,
                                int64_t memory_budget_bytes) {
  Helper* h = nullptr;
  {
    std::unique_lock<std::mutex> lock(mu_);
    free_.wait(lock, [this] {
      for (const Helper& x : helpers_)
        if (!x.busy) return true;
      return false;
    });
    for (Helper& x : helpers_) {
      if (!x.busy) {
        h = &x;
        break;
      }
    }
    h->busy = true;
  }
  Status s = OkStatus();
  // A helper that died while idle (killed from outside, or gone between
  // requests) has nothing to do with this request: replace it.
  int idle_status = 0;
  Reap(h, &idle_status);
  if (h->pid < 0) {
    s = Spawn(h);
    if (s.ok()) ++starts_;
  }
  if (s.ok()) {
    s = Exchange(h, kind, what, item_bytes, send, receive, cancel, deadline,
                 memory_budget_bytes);
  }
  if (s.code == StatusCode::kResourceExhausted &&
      s.message.find("ran out of memory") != std::string::npos) {
    // Either limit may have been the one the helper hit: name both.
    std::vector<std::string> limits;
    if (memory_budget_bytes > 0) {
      limits.push_back("the request's memory budget is " +
                       std::to_string(memory_budget_bytes >> 20) + " MiB");
    }
    if (config_.memory_limit_bytes > 0) {
      limits.push_back("a helper process may map " +
                       std::to_string(config_.memory_limit_bytes >> 20) +
                       " MiB" +
                       (config_.memory_limit_setting.empty()
                            ? std::string()
                            : " (" + config_.memory_limit_setting + ")"));
    }
    for (size_t i = 0; i < limits.size(); ++i) {
      s.message += (i == 0 ? " (" : "; ") + limits[i];
    }
    if (!limits.empty()) s.message += ")";
  }
  {
    std::lock_guard<std::mutex> lock(mu_);
    h->busy = false;
  }
  free_.notify_one();
  return s;
}

Status DelaunayHelperPool::Exchange(Helper* h, HelperRequest kind,
                                    const std::string& what, size_t item_bytes,
                                    const SendFn& send,
                                    const ReceiveFn& receive,
                                    const std::atomic<bool>* cancel,
                                    Clock::time_point deadline,
                                    int64_t memory_budget_bytes) {
  // The helper stopped answering: say how it ended, as the kernel tells it
  // (we kill it only if it has not ended by itself within ~50 ms).
  auto died = [&](const std::string& why) {
    int status = 0;
    bool ended = false;
    for (int i = 0; i < 50 && !ended; ++i) {
      ended = Reap(h, &status);
      if (!ended) ::usleep(1000);
    }
    if (!ended) {
      Kill(h);
      return Internal("the helper process stopped answering during " + what +
                      " (" + why + ") and was restarted");
    }
    std::string how;
    if (WIFEXITED(status) && WEXITSTATUS(status) == kExitInputOutOfMemory) {
      return MakeStatus(StatusCode::kResourceExhausted,
                        "the helper process running " + what +
                            " ran out of memory holding its input");
    }
    if (WIFEXITED(status)) {
      // (A sanitizer build's helper turns a crash into an exit code.)
      how = "exited with code " + std::to_string(WEXITSTATUS(status)) +
            " while working on this input";
    } else if (WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) {
      how =
          "was killed (SIGKILL: out of memory, or stopped from outside; "
          "retrying may succeed)";
    } else if (WIFSIGNALED(status)) {
      how = "crashed on this input (signal " +
            std::to_string(WTERMSIG(status)) + ", " +
            strsignal(WTERMSIG(status)) + ")";
    }
    return Internal("the helper process running " + what + " " + how);
  };
  const auto code_of_kind = static_cast<uint32_t>(kind);
  const auto budget =
      static_cast<uint64_t>(std::max<int64_t>(0, memory_budget_bytes));
  if (!WriteAll(h->to_child, &code_of_kind, sizeof code_of_kind) ||
      !WriteAll(h->to_child, &budget, sizeof budget) || !send(h->to_child)) {
    return died("writing the request failed");
  }
  // Reads `len` bytes, polling so that a cancel or deadline kills the helper.
  const ReadFn read = [&](void* data, size_t len) -> Status {
    char* p = static_cast<char*>(data);
    while (len > 0) {
      if (cancel != nullptr && cancel->load()) {
        Kill(h);
        return MakeStatus(StatusCode::kCancelled, "cancelled by the caller");
      }
      if (Clock::now() >= deadline) {
        Kill(h);
        return MakeStatus(StatusCode::kDeadlineExceeded,
                          "deadline exceeded during " + what);
      }
      pollfd pfd{h->from_child, POLLIN, 0};
      const int ready = ::poll(&pfd, 1, 10);
      if (ready < 0 && errno != EINTR) return died("poll failed");  // NOLINT
      if (ready <= 0) continue;
      const ssize_t r = ::read(h->from_child, p, len);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) {
        return died("its pipe closed");
      }
      p += r;
      len -= static_cast<size_t>(r);
    }
    return OkStatus();
  };
  int32_t code = 0;
  uint32_t len = 0;
  uint64_t count = 0;
  Status s = read(&code, sizeof code);
  if (s.ok()) s = read(&len, sizeof len);
  std::string message(s.ok() ? len : 0, '\0');
  if (s.ok()) s = read(message.data(), len);
  if (s.ok()) s = read(&count, sizeof count);
  if (!s.ok()) return s;
  // A refusal carries no items (WriteReply): its status is the answer. One
  // that claims items breaks the protocol: the helper is not reused.
  if (code != 0) {
    if (count != 0) Kill(h);
    return MakeStatus(static_cast<StatusCode>(code), message);
  }
  const uint64_t reply_bytes = count * item_bytes;
  if (budget > 0 && reply_bytes > budget) {
    Kill(h);  // the rest of its reply is not read
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the answer of " + what + " takes " +
                          std::to_string(reply_bytes >> 20) +
                          " MiB, over the budget");
  }
  return receive(count, read);
}

}  // namespace dot
