// SPDX-License-Identifier: AGPL-3.0-or-later
#include "listener_watchdog.h"

#include <dirent.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

namespace dot::server {
namespace {

// Inodes of this process's sockets ("socket:[123]" links in /proc/self/fd).
bool SocketInodes(std::set<uint64_t>* inodes) {
  DIR* dir = ::opendir("/proc/self/fd");
  if (dir == nullptr) return false;
  char target[64];
  while (const dirent* e = ::readdir(dir)) {
    const std::string link = std::string("/proc/self/fd/") + e->d_name;
    const ssize_t n = ::readlink(link.c_str(), target, sizeof target - 1);
    if (n <= 0) continue;
    target[n] = '\0';
    if (std::strncmp(target, "socket:[", 8) == 0) {
      inodes->insert(std::strtoull(target + 8, nullptr, 10));
    }
  }
  ::closedir(dir);
  return true;
}

}  // namespace

int64_t AcceptQueueLength(int port) {
  std::set<uint64_t> mine;
  if (!SocketInodes(&mine)) return -1;
  for (const char* table : {"/proc/net/tcp", "/proc/net/tcp6"}) {
    std::ifstream in(table);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      // sl local rem st tx:rx tr:when retrnsmt uid timeout inode ...
      std::istringstream f(line);
      std::string sl, local, remote, state, queues, timer, retr, uid, timeout;
      uint64_t inode = 0;
      f >> sl >> local >> remote >> state >> queues >> timer >> retr >> uid >>
          timeout >> inode;
      if (state != "0A" || mine.count(inode) == 0) continue;  // LISTEN, ours
      const size_t colon = local.rfind(':');
      if (colon == std::string::npos ||
          std::strtol(local.c_str() + colon + 1, nullptr, 16) != port) {
        continue;
      }
      const size_t q = queues.find(':');
      return q == std::string::npos
                 ? -1
                 : std::strtoll(queues.c_str() + q + 1, nullptr, 16);
    }
  }
  return -1;
}

ListenerWatchdog::ListenerWatchdog(
    int port, ListenerWatchdogOptions options,
    std::function<void(const std::string&)> on_deaf)
    : port_(port), options_(options), on_deaf_(std::move(on_deaf)) {
  thread_ = std::thread([this] { Watch(); });
}

ListenerWatchdog::~ListenerWatchdog() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void ListenerWatchdog::Watch() {
  using Clock = std::chrono::steady_clock;
  Clock::time_point waiting_since{};  // queue non-empty since; {}: empty
  std::unique_lock<std::mutex> lock(mu_);
  while (!cv_.wait_for(lock, options_.interval, [this] { return stop_; })) {
    const int64_t queued = AcceptQueueLength(port_);
    if (queued < 0) continue;  // unreadable: no evidence either way
    if (queued == 0) {
      waiting_since = {};
      continue;
    }
    const auto now = Clock::now();
    if (waiting_since == Clock::time_point{}) waiting_since = now;
    if (now - waiting_since >= options_.patience) {
      lock.unlock();
      on_deaf_("the gRPC listener on port " + std::to_string(port_) +
               " has stopped accepting connections (" + std::to_string(queued) +
               " waiting for " +
               std::to_string(options_.patience.count() / 1000) +
               " s, as after running out of file descriptors)");
      return;
    }
  }
}

}  // namespace dot::server
