// SPDX-License-Identifier: AGPL-3.0-or-later
#include "measure.h"

#include <algorithm>

#include "dot/elapsed.h"
#include "heap_meter.h"

namespace dot::bench {

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k = 0;
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++k;
  }
  const double d = k * sxx - sx * sx;
  if (k < 2 || d <= 0) return NAN;
  return (k * sxy - sx * sy) / d;
}

Sample Measure(int reps, double long_run_s, double cap_s,
               const std::function<void()>& fn) {
  std::vector<double> ms, heap;
  Sample s;
  for (int r = 0; r < reps; ++r) {
    ResetHeapPeak();
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    ms.push_back(MsSince(t0));
    heap.push_back(static_cast<double>(HeapPeakBytes()));
    if (ms.back() > 1000 * cap_s) {
      s.capped = true;
      break;
    }
    if (ms.back() > 1000 * long_run_s) reps = std::min(reps, 3);
  }
  s.ms = Median(ms);
  s.heap = Median(heap);
  s.runs = static_cast<int>(ms.size());
  return s;
}

}  // namespace dot::bench
