// SPDX-License-Identifier: AGPL-3.0-or-later
// Cancellation, deadline and progress polling for long loops.
#ifndef DOT_CORE_UTIL_RUN_CONTROL_H_
#define DOT_CORE_UTIL_RUN_CONTROL_H_

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "dot/control.h"
#include "dot/elapsed.h"  // IWYU pragma: export
#include "dot/status.h"

namespace dot {

// Whether the caller asked the run to stop: cancel flag set or deadline
// passed. Reads only `control`, so worker threads may call it too.
inline bool StopRequested(const Control& control) {
  return (control.cancel != nullptr && control.cancel->load()) ||
         std::chrono::steady_clock::now() >= control.deadline;
}

// Loops call Tick() every iteration; every `kStride` ticks it reads the clock,
// checks the cancel flag and deadline, and reports progress at most every
// 50 ms. Cheap enough for inner loops, frequent enough for a ~10 ms response.
class RunTicker {
 public:
  RunTicker(const Control& control, Stage stage)
      : control_(control), stage_(stage), activity_(StageName(stage)) {}
  // For work that is not one of the polygon pipeline's stages (repair, the
  // border walk, refinement, ...): `activity` names it in the deadline
  // message and must outlive the ticker; no progress is reported.
  RunTicker(const Control& control, std::string_view activity)
      : control_(control),
        stage_(Stage::kValidate),
        activity_(activity),
        reports_progress_(false) {}

  // Returns false once the run must stop; status() then says why.
  bool Tick(double fraction_done = -1) {
    if (++count_ < kStride) return true;
    count_ = 0;
    return Poll(fraction_done);
  }
  // Tick for `units` iterations at once, counted in the caller's `work`:
  // for loops of a few instructions per iteration, which keep the count in
  // a local (a register) where a member would cost a store each time.
  bool Advance(int64_t& work, int64_t units, double fraction_done = -1) {
    work += units;
    if (work < kStride) return true;
    work = 0;
    return Poll(fraction_done);
  }
  bool Poll(double fraction_done = -1) {
    if (control_.cancel != nullptr && control_.cancel->load()) {
      status_ = MakeStatus(StatusCode::kCancelled, "cancelled by the caller");
      return false;
    }
    const auto now = std::chrono::steady_clock::now();
    if (now >= control_.deadline) {
      status_ =
          MakeStatus(StatusCode::kDeadlineExceeded,
                     "deadline exceeded during " + std::string(activity_));
      return false;
    }
    if (reports_progress_ && control_.progress && fraction_done >= 0 &&
        now - last_report_ >= std::chrono::milliseconds(50)) {
      last_report_ = now;
      control_.progress(stage_, fraction_done);
    }
    return true;
  }
  const Status& status() const { return status_; }

 private:
  static constexpr int kStride = 4096;
  const Control& control_;
  Stage stage_;
  std::string_view activity_;
  bool reports_progress_ = true;
  int count_ = 0;
  std::chrono::steady_clock::time_point last_report_{};
  Status status_;
};

// Runs body(i) for i in [0, n) with a Poll between blocks of 64 Ki, not a
// Tick per iteration; body returns false to stop. False when the run
// must stop (ticker.status() says why) or body stopped.
template <typename Body>
bool ForEachPolled(RunTicker& ticker, size_t n, Body&& body) {
  constexpr size_t kBlock = size_t{1} << 16;
  for (size_t begin = 0; begin < n; begin += kBlock) {
    if (!ticker.Poll()) return false;
    const size_t end = n - begin < kBlock ? n : begin + kBlock;
    for (size_t i = begin; i < end; ++i) {
      if (!body(i)) return false;
    }
  }
  return true;
}

}  // namespace dot

#endif  // DOT_CORE_UTIL_RUN_CONTROL_H_
