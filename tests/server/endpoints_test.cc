// SPDX-License-Identifier: AGPL-3.0-or-later
// The server's endpoints besides the RPCs: health by service name, one
// server per port, and a /metrics endpoint that slow clients cannot hold.
#include <arpa/inet.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <iostream>
#include <string>
#include <thread>

#include "fixtures/service_fixture.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace dot {
namespace {

using grpc::health::v1::HealthCheckResponse;
using Clock = std::chrono::steady_clock;

// A TCP connection to loopback (127.0.0.1, or ::1 with ipv6) port; -1 when
// refused.
int Connect(int port, bool ipv6 = false) {
  const int fd = ::socket(ipv6 ? AF_INET6 : AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  sockaddr_in6 addr6{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr6.sin6_family = AF_INET6;
  addr6.sin6_port = htons(static_cast<uint16_t>(port));
  addr6.sin6_addr = in6addr_loopback;
  const int rc =
      ipv6 ? ::connect(fd, reinterpret_cast<sockaddr*>(&addr6), sizeof addr6)
           : ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  if (rc != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

TEST(EndpointsTest, HealthAnswersForTheServiceName) {
  auto s = testing::StartServer(testing::LoopbackConfig());
  auto health = grpc::health::v1::Health::NewStub(s.channel);
  auto check = [&](const std::string& service) {
    grpc::ClientContext c;
    grpc::health::v1::HealthCheckRequest request;
    request.set_service(service);
    HealthCheckResponse r;
    const grpc::Status st = health->Check(&c, request, &r);
    EXPECT_TRUE(st.ok()) << service << ": " << st.error_message();
    return r.status();
  };
  EXPECT_EQ(check(""), HealthCheckResponse::SERVING);
  EXPECT_EQ(check("dot.v1.Triangulator"), HealthCheckResponse::SERVING);
  s.server->Drain(std::chrono::milliseconds(0));
}

TEST(EndpointsTest, SecondServerOnTheSamePortIsRefused) {
  auto first = testing::StartServer(testing::LoopbackConfig());
  auto config = testing::LoopbackConfig();
  config.listen = "127.0.0.1:" + std::to_string(first.server->port());
  std::string error;
  auto second = server::DotServer::Start(config, &error);
  EXPECT_EQ(second, nullptr);
  EXPECT_NE(error.find("cannot listen"), std::string::npos) << error;
}

// The whole answer of the metrics endpoint to one raw HTTP request.
std::string HttpExchange(int port, const std::string& request,
                         bool ipv6 = false) {
  const int fd = Connect(port, ipv6);
  if (fd < 0) return "";
  if (::write(fd, request.data(), request.size()) !=
      static_cast<ssize_t>(request.size())) {
    ::close(fd);
    return "";
  }
  std::string answer;
  char buf[4096];
  ssize_t got;
  while ((got = ::read(fd, buf, sizeof buf)) > 0) answer.append(buf, got);
  ::close(fd);
  return answer;
}

TEST(EndpointsTest, MetricsPortAnswersEveryMethodAndPathWithoutCrashing) {
  // Before: each of these was a SIGSEGV of the whole server (civetweb's own
  // 404/405 answers overflow its thread stacks).
  auto config = testing::LoopbackConfig();
  config.metrics.port = testing::FreeLoopbackPort();
  auto s = testing::StartServer(config);
  ASSERT_TRUE(s.server);
  const int port = config.metrics.port;
  struct Case {
    const char* request_line;
    const char* status;
  };
  const Case cases[] = {
      {"HEAD /metrics", "HTTP/1.1 200"},
      {"GET /", "HTTP/1.1 200"},
      {"HEAD /", "HTTP/1.1 200"},
      {"GET /favicon.ico", "HTTP/1.1 404"},
      {"POST /metrics", "HTTP/1.1 405"},
      {"OPTIONS /metrics", "HTTP/1.1 405"},
      {"PUT /metrics", "HTTP/1.1 405"},
      {"DELETE /", "HTTP/1.1 405"},
      {"PATCH /x/../metrics", "HTTP/1.1 405"},
      {"GET /metrics/x", "HTTP/1.1 404"},
      {"OPTIONS *", ""},  // civetweb closes the connection: no answer
  };
  for (const Case& c : cases) {
    const std::string answer = HttpExchange(
        port, std::string(c.request_line) +
                  " HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\n\r\n");
    EXPECT_EQ(answer.rfind(c.status, 0), 0u)
        << c.request_line << " -> " << answer.substr(0, 80);
    if (std::string(c.request_line).rfind("HEAD", 0) == 0) {
      EXPECT_EQ(answer.find("\r\n\r\n") + 4, answer.size())
          << c.request_line << ": a HEAD answer has no body";
    }
  }
  // Also under AddressSanitizer: prometheus-cpp's own handler, which
  // formats with mg_printf, overflowed civetweb's 100 KB stacks there (a
  // CI failure); the server now answers GET /metrics itself.
  const std::string metrics =
      HttpExchange(port, "GET /metrics HTTP/1.0\r\n\r\n");
  EXPECT_EQ(metrics.rfind("HTTP/1.1 200", 0), 0u) << metrics.substr(0, 80);
  EXPECT_NE(metrics.find("Content-Type: text/plain; version=0.0.4"),
            std::string::npos);
  EXPECT_NE(metrics.find("dot_delaunay_helper_starts_total"),
            std::string::npos);
  const size_t header_end = metrics.find("\r\n\r\n");
  ASSERT_NE(header_end, std::string::npos);
  EXPECT_NE(metrics.find("Content-Length: " +
                         std::to_string(metrics.size() - header_end - 4)),
            std::string::npos)
      << "the length names the body";
}

TEST(EndpointsTest, MetricsAnswerWhileSlowClientsHoldConnections) {
  auto config = testing::LoopbackConfig();
  config.metrics.port = testing::FreeLoopbackPort();
  auto s = testing::StartServer(config);
  ASSERT_TRUE(s.server);
  EXPECT_EQ(config.metrics.bind, "127.0.0.1");  // the default
  // Slow clients: a partial request line, then silence. Before: 40 of them
  // delayed a scrape by 20 s (4 threads, each held 2 s by one of them).
  std::vector<int> slow;
  for (int i = 0; i < 40; ++i) {
    const int fd = Connect(config.metrics.port);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, "GET /met", 8), 8);
    slow.push_back(fd);
  }
  const auto t0 = Clock::now();
  std::string body;
  const int fd = Connect(config.metrics.port);
  ASSERT_GE(fd, 0);
  const std::string get = "GET /metrics HTTP/1.0\r\n\r\n";
  ASSERT_EQ(::write(fd, get.data(), get.size()),
            static_cast<ssize_t>(get.size()));
  char buf[4096];
  ssize_t got;
  while ((got = ::read(fd, buf, sizeof buf)) > 0) body.append(buf, got);
  ::close(fd);
  const double seconds =
      std::chrono::duration<double>(Clock::now() - t0).count();
  std::cout << "scrape with 40 slow clients: " << seconds
            << " s (about 40 / threads x the request timeout, 2.5 s)\n";
  EXPECT_LT(seconds, 15.0);  // a generous bound: before, 20 s
  EXPECT_NE(body.find("dot_delaunay_helper_starts_total"), std::string::npos)
      << body.substr(0, 300);
  for (int f : slow) ::close(f);
}

TEST(EndpointsTest, MetricsBindToAnIpv6AddressWhenTheBuildCan) {
  // Before: --metrics-bind ::1 passed the flag checks and failed at start
  // with civetweb's "null context" (Debian builds it without IPv6).
  if (!server::MetricsSupportIpv6()) {
    GTEST_SKIP() << "civetweb without IPv6 (ConfigTest checks the refusal)";
  }
  auto config = testing::LoopbackConfig();
  config.metrics.port = testing::FreeLoopbackPort();
  config.metrics.bind = "::1";
  auto s = testing::StartServer(config);
  ASSERT_TRUE(s.server);
  const std::string answer = HttpExchange(
      config.metrics.port, "HEAD /metrics HTTP/1.0\r\n\r\n", /*ipv6=*/true);
  EXPECT_EQ(answer.rfind("HTTP/1.1 200", 0), 0u) << answer.substr(0, 80);
}

}  // namespace
}  // namespace dot
