// SPDX-License-Identifier: AGPL-3.0-or-later
// Repeated measurement: medians of several runs, each run's wall time and
// peak heap, and the log-log slope of a series.
#ifndef DOT_BENCH_MEASURE_H_
#define DOT_BENCH_MEASURE_H_

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace dot::bench {

double Median(std::vector<double> v);  // NaN when empty

// Least-squares slope of log(y) against log(x) over the positive pairs;
// NaN with fewer than two.
double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y);

struct Sample {
  double ms = NAN;      // median wall time
  double heap = NAN;    // median peak heap bytes
  int runs = 0;         // how many runs the medians are over
  bool capped = false;  // a run exceeded the time cap: larger sizes skipped
};

// Runs `fn` up to `reps` times (fewer when one run exceeds `long_run_s`:
// then 3, and 1 past `cap_s`) and returns the medians.
Sample Measure(int reps, double long_run_s, double cap_s,
               const std::function<void()>& fn);

}  // namespace dot::bench

#endif  // DOT_BENCH_MEASURE_H_
