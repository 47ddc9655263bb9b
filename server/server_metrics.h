// SPDX-License-Identifier: AGPL-3.0-or-later
// Prometheus metrics of the server (prometheus-cpp), optionally exposed over
// HTTP at /metrics.
#ifndef DOT_SERVER_SERVER_METRICS_H_
#define DOT_SERVER_SERVER_METRICS_H_

#include <prometheus/counter.h>
#include <prometheus/gauge.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include <memory>
#include <mutex>
#include <string>

#include "dot/space_cache.h"

class CivetServer;

namespace dot::server {

struct MetricsOptions {
  int port = 9090;  // Prometheus /metrics over HTTP; 0: off
  // Address it listens on: loopback unless opened on purpose (the compose
  // and Kubernetes manifests set DOT_METRICS_BIND=0.0.0.0).
  std::string bind = "127.0.0.1";
  // HTTP threads, apart from gRPC's, each held by one connection until it
  // sends its request or `request_timeout_ms` passes: N silent connections
  // delay a scrape by about N / threads x the timeout.
  int threads = 16;
  int request_timeout_ms = 1000;
};

// Whether the metrics endpoint can bind an IPv6 address (Debian's civetweb
// is built without IPv6).
bool MetricsSupportIpv6();

class ServerMetrics {
 public:
  ~ServerMetrics();
  // Exposes /metrics on bind:port unless port is 0; throws when it cannot.
  explicit ServerMetrics(const MetricsOptions& options);

  void RequestDone(const std::string& rpc, const std::string& status,
                   double seconds);
  // A call stopped before it finished, by reason (client_cancel,
  // client_deadline, server_budget, drain, client_gone).
  void RequestStopped(const std::string& rpc, const std::string& reason);
  prometheus::Gauge& queue_depth() { return *queue_depth_; }
  prometheus::Gauge& inflight() { return *inflight_; }
  prometheus::Gauge& busy_threads() { return *busy_threads_; }
  // The helper pool's running total of starts; counted as a delta.
  void HelperStarts(int64_t total);
  // One search-space cache lookup, and the cache's size after it.
  void CacheLookup(bool hit, const SpaceCache::Counters& counters);
  std::string Scrape() const;  // the text format, for tests and logs

 private:
  std::shared_ptr<prometheus::Registry> registry_;
  std::unique_ptr<CivetServer> http_;  // after registry_: stops first
  prometheus::Family<prometheus::Counter>* requests_;
  prometheus::Family<prometheus::Counter>* stopped_;
  prometheus::Family<prometheus::Histogram>* latency_;
  prometheus::Gauge* queue_depth_;
  prometheus::Gauge* inflight_;
  prometheus::Gauge* busy_threads_;
  prometheus::Counter* helper_starts_;
  std::mutex helper_mu_;
  int64_t helper_starts_seen_ = 0;
  prometheus::Counter* cache_hits_;
  prometheus::Counter* cache_misses_;
  prometheus::Gauge* cache_bytes_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_SERVER_METRICS_H_
