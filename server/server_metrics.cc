// SPDX-License-Identifier: AGPL-3.0-or-later
#include "server_metrics.h"

#include <CivetServer.h>
#include <civetweb.h>
#include <prometheus/text_serializer.h>

#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "process_metrics.h"

namespace dot::server {
namespace {

const prometheus::Histogram::BucketBoundaries kLatencyBuckets = {
    0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25,
    0.5,   1,      2.5,   5,    10,    30,   60};

// Debian's civetweb 1.15 runs each request on a 100 KB thread stack, and
// both its own answers (404 for `GET /`, 405 for `HEAD /metrics`) and
// prometheus-cpp's handler format with mg_printf, whose vsnprintf overflows
// that stack (a `curl -I` was a SIGSEGV of the whole server; under
// AddressSanitizer even `GET /metrics` was). So the endpoint is a bare
// CivetServer and every request is answered here, before civetweb's
// dispatch: the answer is assembled in a std::string and sent with
// mg_write, nothing is formatted on civetweb's stack.
int Answer(mg_connection* conn) {
  const mg_request_info* info = mg_get_request_info(conn);
  const std::string_view method =
      info && info->request_method ? info->request_method : "";
  const std::string_view uri = info && info->local_uri ? info->local_uri : "";
  const bool read = method == "GET" || method == "HEAD";
  int status = 200;
  const char* reason = "OK";
  const char* type = "text/plain; charset=utf-8";
  std::string body;
  const char* allow = "";
  if (uri == "/metrics" && read) {
    type = "text/plain; version=0.0.4; charset=utf-8";
    const auto* server = static_cast<const CivetServer*>(info->user_data);
    body =
        static_cast<const ServerMetrics*>(server->getUserContext())->Scrape();
  } else if (uri == "/" && read) {
    type = "text/html; charset=utf-8";
    body =
        "<!doctype html><title>dot-server</title>"
        "<p>dot-server metrics: <a href=\"/metrics\">/metrics</a></p>\n";
  } else if (uri == "/" || uri == "/metrics") {
    status = 405;
    reason = "Method Not Allowed";
    body = "only GET and HEAD are served here\n";
    allow = "Allow: GET, HEAD\r\n";
  } else {
    status = 404;
    reason = "Not Found";
    body = "not found: the metrics are at /metrics\n";
  }
  std::string answer = "HTTP/1.1 " + std::to_string(status) + " " + reason +
                       "\r\nContent-Type: " + type +
                       "\r\nContent-Length: " + std::to_string(body.size()) +
                       "\r\n" + allow + "Connection: close\r\n\r\n";
  if (method != "HEAD") answer.append(body);
  mg_write(conn, answer.data(), answer.size());
  return status;
}

}  // namespace

ServerMetrics::ServerMetrics(const MetricsOptions& options)
    : registry_(std::make_shared<prometheus::Registry>()) {
  requests_ = &prometheus::BuildCounter()
                   .Name("dot_requests_total")
                   .Help(
                       "Requests (batch items count one each) by RPC and "
                       "final status")
                   .Register(*registry_);
  stopped_ = &prometheus::BuildCounter()
                  .Name("dot_requests_stopped_total")
                  .Help(
                      "Requests stopped before they finished, by RPC and "
                      "reason (client_cancel, client_deadline, "
                      "server_budget, drain, client_gone)")
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
  prometheus::BuildGauge()
      .Name("dot_build_info")
      .Help(
          "Always 1; the labels say which build serves: version, commit, "
          "the Delaunay backends compiled in")
      .Register(*registry_)
      .Add({{"version", DOT_VERSION},
            {"commit", DOT_GIT_COMMIT},
            {"backends", DOT_WITH_TETGEN ? "cgal,tetgen" : "cgal"}})
      .Set(1);
  // Every RPC's series exist from the start (at zero), so rates and alerts
  // see a server that has served nothing yet.
  for (const char* rpc :
       {"Triangulate", "TriangulateBatch", "FillHoles", "SurfaceNetwork"}) {
    requests_->Add({{"rpc", rpc}, {"status", "OK"}});
    latency_->Add({{"rpc", rpc}}, kLatencyBuckets);
  }
  if (options.port > 0) {
    // Its own small pool of HTTP threads, each giving up on a client that
    // is silent for `request_timeout_ms`, and no keep-alive: slow or idle
    // scrapers cannot hold the endpoint (the gRPC port is separate).
    CivetCallbacks callbacks{};
    callbacks.begin_request = Answer;
    // civetweb writes an IPv6 address in brackets.
    const std::string host = options.bind.find(':') == std::string::npos
                                 ? options.bind
                                 : "[" + options.bind + "]";
    http_ = std::make_unique<CivetServer>(
        std::vector<std::string>{
            "listening_ports", host + ":" + std::to_string(options.port),
            "num_threads", std::to_string(options.threads),
            "request_timeout_ms", std::to_string(options.request_timeout_ms),
            "enable_keep_alive", "no"},
        &callbacks, this);
  }
}

// The HTTP threads stop before the registry they read goes.
ServerMetrics::~ServerMetrics() { http_.reset(); }

bool MetricsSupportIpv6() { return mg_check_feature(8) != 0; }

void ServerMetrics::RequestDone(const std::string& rpc,
                                const std::string& status, double seconds) {
  requests_->Add({{"rpc", rpc}, {"status", status}}).Increment();
  latency_->Add({{"rpc", rpc}}, kLatencyBuckets).Observe(seconds);
}

void ServerMetrics::RequestStopped(const std::string& rpc,
                                   const std::string& reason) {
  stopped_->Add({{"rpc", rpc}, {"reason", reason}}).Increment();
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
  std::vector<prometheus::MetricFamily> families = registry_->Collect();
  // Read on a thread of its own: civetweb's request threads have 100 KB
  // stacks, which /proc parsing overflowed under AddressSanitizer. No
  // thread to be had: no process metrics this scrape.
  std::vector<prometheus::MetricFamily> process;
  try {
    std::thread reader([&process] { process = CollectProcessMetrics(); });
    reader.join();
  } catch (const std::system_error&) {
  }
  for (auto& f : process) families.push_back(std::move(f));
  return prometheus::TextSerializer().Serialize(families);
}

}  // namespace dot::server
