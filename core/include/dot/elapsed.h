// SPDX-License-Identifier: AGPL-3.0-or-later
// Milliseconds since a steady-clock time: the one timer of the core, the
// server, the client and the benchmarks (reports, logs, --verbose lines).
#ifndef DOT_ELAPSED_H_
#define DOT_ELAPSED_H_

#include <chrono>

namespace dot {

// A duration in milliseconds.
inline double Ms(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

inline double MsSince(std::chrono::steady_clock::time_point t0) {
  return Ms(std::chrono::steady_clock::now() - t0);
}

}  // namespace dot

#endif  // DOT_ELAPSED_H_
