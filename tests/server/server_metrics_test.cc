// SPDX-License-Identifier: AGPL-3.0-or-later
// What /metrics says before any request: the process_* metrics from /proc,
// the build, and every RPC's series at zero.
#include "server_metrics.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <ctime>
#include <regex>
#include <string>

namespace dot::server {
namespace {

// The value of the first sample whose line starts with `series`.
double Sample(const std::string& text, const std::string& series) {
  const size_t at = text.find("\n" + series + " ");
  if (at == std::string::npos) return -1;
  return std::strtod(text.c_str() + at + series.size() + 2, nullptr);
}

TEST(ServerMetricsTest, ProcessMetricsComeFromProc) {
  MetricsOptions options;
  options.port = 0;
  const ServerMetrics metrics(options);
  const std::string text = metrics.Scrape();
  EXPECT_GT(Sample(text, "process_resident_memory_bytes"), 1 << 20) << text;
  EXPECT_GT(Sample(text, "process_virtual_memory_bytes"),
            Sample(text, "process_resident_memory_bytes"));
  EXPECT_GE(Sample(text, "process_open_fds"), 3);
  EXPECT_GE(Sample(text, "process_max_fds"), Sample(text, "process_open_fds"));
  EXPECT_GE(Sample(text, "process_cpu_seconds_total"), 0);
  // This test process started before now, and not days ago.
  const double started = Sample(text, "process_start_time_seconds");
  const auto now = static_cast<double>(std::time(nullptr));
  EXPECT_LE(started, now + 1);
  EXPECT_GT(started, now - 3600);
  EXPECT_NE(text.find("# TYPE process_cpu_seconds_total counter"),
            std::string::npos);
}

TEST(ServerMetricsTest, BuildInfoAndEveryRpcFromTheStart) {
  MetricsOptions options;
  options.port = 0;
  const ServerMetrics metrics(options);
  const std::string text = metrics.Scrape();
  EXPECT_TRUE(std::regex_search(
      text, std::regex("\ndot_build_info\\{backends=\"cgal[^\"]*\",commit=\"[^"
                       "\"]+\",version=\"[0-9.]+\"\\} 1\n")))
      << text;
  for (const char* rpc :
       {"Triangulate", "TriangulateBatch", "FillHoles", "SurfaceNetwork"}) {
    EXPECT_EQ(Sample(text, std::string("dot_requests_total{rpc=\"") + rpc +
                               "\",status=\"OK\"}"),
              0)
        << rpc;
    EXPECT_EQ(Sample(text, std::string("dot_request_duration_seconds_count{"
                                       "rpc=\"") +
                               rpc + "\"}"),
              0)
        << rpc;
  }
}

}  // namespace
}  // namespace dot::server
