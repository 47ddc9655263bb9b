// SPDX-License-Identifier: AGPL-3.0-or-later
// TetGen in a helper process, for the fuzz targets: what dot-server's
// Delaunay helper processes give it (server/compute/delaunay_helpers.cc).
// TetGen 1.5.0 (Debian's libtet) aborts on some degenerate point sets (an
// assertion in its symbolic perturbation, tetgenmesh::insphere_s); the
// server survives that as an INTERNAL status naming the crash, and so do
// the fuzzers, which test our code around TetGen rather than TetGen itself.
// One helper, forked on first use and again after each crash: a fork per
// call would cost more than the call.
#ifndef DOT_TESTS_FUZZ_TETGEN_CHILD_H_
#define DOT_TESTS_FUZZ_TETGEN_CHILD_H_

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "dot/triangulate.h"

namespace dot::fuzz {

namespace internal {

inline bool WriteAll(int fd, const void* data, size_t len) {
  const char* p = static_cast<const char*>(data);
  while (len > 0) {
    const ssize_t k = ::write(fd, p, len);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    len -= static_cast<size_t>(k);
  }
  return true;
}

inline bool ReadAll(int fd, void* data, size_t len) {
  char* p = static_cast<char*>(data);
  while (len > 0) {
    const ssize_t k = ::read(fd, p, len);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    len -= static_cast<size_t>(k);
  }
  return true;
}

// The helper: default signal dispositions (libFuzzer's and the sanitizers'
// handlers would report TetGen's abort as the fuzzer's crash), then one
// request after another until the pipe closes; _exit skips the leak check
// of the forked heap.
[[noreturn]] inline void ServeRequests(int in, int out) {
  for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGALRM}) {
    ::signal(sig, SIG_DFL);
  }
  for (;;) {
    uint64_t n = 0;
    if (!ReadAll(in, &n, sizeof n) || n > (uint64_t{1} << 24)) ::_exit(0);
    std::vector<Vec3> points(n);
    if (!ReadAll(in, points.data(), n * sizeof(Vec3))) ::_exit(0);
    ::alarm(30);  // never hang for good
    Tetrahedralization t;
    const Status s = TetgenTetrahedralize(points, &t);
    ::alarm(0);
    const auto code = static_cast<int32_t>(s.code);
    const auto length = static_cast<uint64_t>(s.message.size());
    const auto count = static_cast<uint64_t>(t.tets.size());
    const bool ok =
        WriteAll(out, &code, sizeof code) &&
        WriteAll(out, &length, sizeof length) &&
        WriteAll(out, s.message.data(), s.message.size()) &&
        WriteAll(out, &count, sizeof count) &&
        WriteAll(out, t.tets.data(), count * sizeof(t.tets[0])) &&
        WriteAll(out, t.neighbors.data(), count * sizeof(t.neighbors[0]));
    if (!ok) ::_exit(1);
  }
}

// One helper process, started on first use and again after it died.
class Helper {
 public:
  ~Helper() { Stop(); }

  Status Tetrahedralize(const std::vector<Vec3>& points,
                        Tetrahedralization* out) {
    if (pid_ <= 0 && !Start()) {
      return MakeStatus(StatusCode::kInternal, "cannot start a TetGen helper");
    }
    const uint64_t n = points.size();
    int32_t code = 0;
    uint64_t length = 0, count = 0;
    std::string message;
    bool complete = WriteAll(to_, &n, sizeof n) &&
                    WriteAll(to_, points.data(), n * sizeof(Vec3)) &&
                    ReadAll(from_, &code, sizeof code) &&
                    ReadAll(from_, &length, sizeof length) &&
                    length < (uint64_t{1} << 20);
    if (complete) {
      message.resize(length);
      complete = ReadAll(from_, message.data(), length) &&
                 ReadAll(from_, &count, sizeof count) &&
                 count < (uint64_t{1} << 26);
    }
    if (complete) {
      out->tets.resize(count);
      out->neighbors.resize(count);
      complete =
          ReadAll(from_, out->tets.data(), count * sizeof(out->tets[0])) &&
          ReadAll(from_, out->neighbors.data(),
                  count * sizeof(out->neighbors[0]));
    }
    if (!complete) {
      *out = {};
      const int status = Stop();
      if (WIFSIGNALED(status)) {
        return MakeStatus(StatusCode::kInternal,
                          "the TetGen helper crashed on this input (signal " +
                              std::to_string(WTERMSIG(status)) + ")");
      }
      return MakeStatus(StatusCode::kInternal, "the TetGen helper failed");
    }
    return MakeStatus(static_cast<StatusCode>(code), std::move(message));
  }

 private:
  bool Start() {
    // A helper that died must not take the fuzzer with it on the next write.
    ::signal(SIGPIPE, SIG_IGN);
    int down[2], up[2];
    if (::pipe(down) != 0) return false;
    if (::pipe(up) != 0) {
      ::close(down[0]);
      ::close(down[1]);
      return false;
    }
    const pid_t pid = ::fork();
    if (pid < 0) {
      for (int fd : {down[0], down[1], up[0], up[1]}) ::close(fd);
      return false;
    }
    if (pid == 0) {
      ::close(down[1]);
      ::close(up[0]);
      ServeRequests(down[0], up[1]);
    }
    ::close(down[0]);
    ::close(up[1]);
    pid_ = pid;
    to_ = down[1];
    from_ = up[0];
    return true;
  }

  // Closes the pipes and reaps the helper; its wait status.
  int Stop() {
    if (pid_ <= 0) return 0;
    ::close(to_);
    ::close(from_);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return status;
  }

  pid_t pid_ = -1;
  int to_ = -1, from_ = -1;
};

}  // namespace internal

// A Control::tetrahedralize running TetGen in a helper process (one per
// fuzzer process, restarted after a crash).
inline Status TetgenInChild(const std::vector<Vec3>& points,
                            Tetrahedralization* out) {
  static internal::Helper* helper = new internal::Helper;
  return helper->Tetrahedralize(points, out);
}

}  // namespace dot::fuzz

#endif  // DOT_TESTS_FUZZ_TETGEN_CHILD_H_
