// SPDX-License-Identifier: AGPL-3.0-or-later
// The timers that bound an upload (FillHoles), so that a slow or silent
// client cannot hold a call: its first message within the server's limit,
// the whole upload within the job's deadline, and at once when the server
// drains. They fire on gRPC's threads; after Disarm (the reactor's OnDone)
// a late one finds nobody instead of a freed reactor.
#ifndef DOT_SERVER_RPC_UPLOAD_TIMERS_H_
#define DOT_SERVER_RPC_UPLOAD_TIMERS_H_

#include <grpcpp/alarm.h>

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>

namespace dot::server {

class UploadTimers {
 public:
  using Time = std::chrono::system_clock::time_point;

  // `on_fire` runs when a set timer fires, under the timers' lock.
  explicit UploadTimers(std::function<void()> on_fire)
      : guard_(std::make_shared<Guard>()) {
    guard_->on_fire = std::move(on_fire);
  }
  ~UploadTimers() { Disarm(); }
  UploadTimers(const UploadTimers&) = delete;
  UploadTimers& operator=(const UploadTimers&) = delete;

  void FirstMessageBy(Time when) { Set(&first_message_, when); }
  // The first message came: the job's deadline bounds the rest.
  void UploadBy(std::chrono::steady_clock::time_point when) {
    first_message_.Cancel();
    Set(&upload_, std::chrono::system_clock::now() +
                      std::chrono::duration_cast<Time::duration>(
                          when - std::chrono::steady_clock::now()));
  }
  // The server drains: fire now. May be called with the runner's lock held.
  void FireNow() { Set(&drain_, std::chrono::system_clock::now()); }
  void Disarm() {
    std::lock_guard<std::mutex> lock(guard_->mu);
    guard_->on_fire = nullptr;
  }

 private:
  // Shared with the alarms' callbacks, which may outlive this.
  struct Guard {
    std::mutex mu;
    std::function<void()> on_fire;
  };
  void Set(grpc::Alarm* alarm, Time when) {
    alarm->Set(when, [guard = guard_](bool fired) {
      std::lock_guard<std::mutex> lock(guard->mu);
      if (fired && guard->on_fire) guard->on_fire();
    });
  }

  std::shared_ptr<Guard> guard_;
  grpc::Alarm first_message_, upload_, drain_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_UPLOAD_TIMERS_H_
