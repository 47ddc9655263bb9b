// SPDX-License-Identifier: AGPL-3.0-or-later
#include "server_metrics.h"

#include <prometheus/text_serializer.h>

namespace dot::server {

ServerMetrics::ServerMetrics(const MetricsOptions& options)
    : registry_(std::make_shared<prometheus::Registry>()) {
  requests_ = &prometheus::BuildCounter()
                   .Name("dot_requests_total")
                   .Help(
                       "Requests (batch items count one each) by RPC and "
                       "final status")
                   .Register(*registry_);
  latency_ = &prometheus::BuildHistogram()
                  .Name("dot_request_duration_seconds")
                  .Help("Time from arrival to the last byte of the answer")
                  .Register(*registry_);
  auto gauge = [this](const char* name, const char* help) {
    return &prometheus::BuildGauge()
                .Name(name)
                .Help(help)
                .Register(*registry_)
                .Add({});
  };
  queue_depth_ = gauge("dot_queue_depth", "Requests waiting for a thread");
  inflight_ = gauge("dot_inflight_requests", "Requests being served");
  busy_threads_ = gauge("dot_busy_threads", "Compute threads at work");
  helper_starts_ = &prometheus::BuildCounter()
                        .Name("dot_delaunay_helper_starts_total")
                        .Help(
                            "Delaunay helper processes started (restarts "
                            "after crashes or cancels included)")
                        .Register(*registry_)
                        .Add({});
  auto& lookups = prometheus::BuildCounter()
                      .Name("dot_space_cache_lookups_total")
                      .Help("Search-space cache lookups by result")
                      .Register(*registry_);
  cache_hits_ = &lookups.Add({{"result", "hit"}});
  cache_misses_ = &lookups.Add({{"result", "miss"}});
  cache_bytes_ =
      gauge("dot_space_cache_bytes", "Memory held by the search-space cache");
  if (options.port > 0) {
    // Its own small pool of HTTP threads, each giving up on a client that
    // is silent for `request_timeout_ms`, and no keep-alive: slow or idle
    // scrapers cannot hold the endpoint (the gRPC port is separate).
    exposer_ = std::make_unique<prometheus::Exposer>(std::vector<std::string>{
        "listening_ports", options.bind + ":" + std::to_string(options.port),
        "num_threads", std::to_string(options.threads), "request_timeout_ms",
        std::to_string(options.request_timeout_ms), "enable_keep_alive", "no"});
    exposer_->RegisterCollectable(registry_);
  }
}

void ServerMetrics::RequestDone(const std::string& rpc,
                                const std::string& status, double seconds) {
  requests_->Add({{"rpc", rpc}, {"status", status}}).Increment();
  static const prometheus::Histogram::BucketBoundaries kBuckets = {
      0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25,
      0.5,   1,      2.5,   5,    10,    30,   60};
  latency_->Add({{"rpc", rpc}}, kBuckets).Observe(seconds);
}

void ServerMetrics::HelperStarts(int64_t total) {
  std::lock_guard<std::mutex> lock(helper_mu_);
  if (total > helper_starts_seen_) {
    helper_starts_->Increment(static_cast<double>(total - helper_starts_seen_));
    helper_starts_seen_ = total;
  }
}

void ServerMetrics::CacheLookup(bool hit, const SpaceCache::Counters& c) {
  (hit ? cache_hits_ : cache_misses_)->Increment();
  cache_bytes_->Set(static_cast<double>(c.bytes));
}

std::string ServerMetrics::Scrape() const {
  return prometheus::TextSerializer().Serialize(registry_->Collect());
}

}  // namespace dot::server
