// SPDX-License-Identifier: AGPL-3.0-or-later
// The standard process_* metrics (CPU, memory, file descriptors, start
// time), read from /proc at each scrape, as Prometheus' client libraries
// name them; prometheus-cpp has none.
#ifndef DOT_SERVER_PROCESS_METRICS_H_
#define DOT_SERVER_PROCESS_METRICS_H_

#include <prometheus/metric_family.h>

#include <vector>

namespace dot::server {

// process_cpu_seconds_total, process_resident_memory_bytes,
// process_virtual_memory_bytes, process_open_fds, process_max_fds,
// process_start_time_seconds; those /proc cannot give are left out.
std::vector<prometheus::MetricFamily> CollectProcessMetrics();

}  // namespace dot::server

#endif  // DOT_SERVER_PROCESS_METRICS_H_
