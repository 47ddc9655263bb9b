// SPDX-License-Identifier: AGPL-3.0-or-later
// Notices a gRPC listener that stopped accepting connections. gRPC 1.51
// stops accepting for good once accept() has failed with EMFILE (grpc/grpc
// #20418, #16058): the process lives on, deaf, health checks over new
// connections fail, and nothing restarts it. The watchdog reads the
// kernel's accept queue of this process's listening socket (the rx_queue
// of its /proc/net/tcp{,6} entry): connections waiting there through a
// whole `patience` mean nobody accepts them, and `on_deaf` is called
// (dot-server then drains and exits non-zero, for its supervisor to
// restart it). Works alike for plaintext and TLS: it never connects.
#ifndef DOT_SERVER_LISTENER_WATCHDOG_H_
#define DOT_SERVER_LISTENER_WATCHDOG_H_

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace dot::server {

struct ListenerWatchdogOptions {
  std::chrono::milliseconds interval{1000};   // between looks at the queue
  std::chrono::milliseconds patience{20000};  // queued this long: deaf
};

// Connections waiting in the accept queue of this process's listening TCP
// socket on `port`; -1 when it cannot be read (no such socket, or no file
// descriptor left to open /proc with).
int64_t AcceptQueueLength(int port);

class ListenerWatchdog {
 public:
  ListenerWatchdog(int port, ListenerWatchdogOptions options,
                   std::function<void(const std::string& why)> on_deaf);
  ~ListenerWatchdog();  // stops watching
  ListenerWatchdog(const ListenerWatchdog&) = delete;
  ListenerWatchdog& operator=(const ListenerWatchdog&) = delete;

 private:
  void Watch();

  const int port_;
  const ListenerWatchdogOptions options_;
  const std::function<void(const std::string&)> on_deaf_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_LISTENER_WATCHDOG_H_
