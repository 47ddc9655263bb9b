// SPDX-License-Identifier: AGPL-3.0-or-later
// Other processes, as the figures that measure whole processes run them:
// a free loopback port, a command's output, a run's wall time and peak
// memory.
#ifndef DOT_BENCH_PROCESS_H_
#define DOT_BENCH_PROCESS_H_

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace dot::bench {

int FreeLoopbackPort();  // 0 when none could be had

// `command`'s standard output (through the shell).
std::string RunCapture(const std::string& command);

// The number after "key": in a JSON text (NaN when absent): enough for the
// flat reports dotctl prints.
double JsonNumber(const std::string& json, const std::string& key);

struct ProcessRun {
  double seconds = NAN;     // wall time, spawn to exit
  double peak_bytes = NAN;  // maximum resident set size
  int exit_code = -1;       // -1: did not start or was killed
};

// Starts argv[0] with `argv` (no shell), its standard output and error
// into the file `output`: its pid, or 0 when it could not start.
int StartProcess(const std::vector<std::string>& argv,
                 const std::string& output);
// Waits for a started process: its wall time counts from `started`.
ProcessRun WaitProcess(int pid, std::chrono::steady_clock::time_point started);
// Both.
ProcessRun RunProcess(const std::vector<std::string>& argv,
                      const std::string& output);

}  // namespace dot::bench

#endif  // DOT_BENCH_PROCESS_H_
