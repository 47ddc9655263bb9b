// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-server's flags land in their option structs, in the units they say.
#include "config.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

namespace dot::server {
namespace {

TEST(ConfigTest, SizeFlagsConvertTheirUnits) {
  CLI::App app;
  ServerConfig c;
  AddServerFlags(app, &c);
  // --chunk-kb binds a size_t: its range once came out as "0 to -1".
  app.parse("--fill-max-faces 1234 --cache-mb 3 --chunk-kb 16",
            /*program_name_included=*/false);
  EXPECT_EQ(c.service.chunk_bytes, size_t{16} << 10);
  EXPECT_EQ(c.service.fill_max_faces, 1234);
  EXPECT_EQ(c.cache_bytes, int64_t{3} << 20);
}

// The error for --metrics-bind `bind` (empty: accepted).
std::string MetricsBindError(const std::string& bind) {
  CLI::App app;
  ServerConfig c;
  AddServerFlags(app, &c);
  app.parse("--delaunay-helpers 0 --metrics-port 9999",
            /*program_name_included=*/false);
  c.metrics.bind = bind;
  return FinalizeConfig(&c);
}

TEST(ConfigTest, MetricsBindMustBeAnAddressTheEndpointCanBind) {
  // Before: 999.1.1.1 was taken, logged as such, and civetweb listened on
  // 231.1.1.1; ::1 failed at start with civetweb's "null context".
  for (const char* bind : {"999.1.1.1", "localhost", "1.2.3", ""}) {
    EXPECT_NE(MetricsBindError(bind).find("is not an IPv4 or IPv6 address"),
              std::string::npos)
        << bind << ": " << MetricsBindError(bind);
  }
  for (const char* bind : {"127.0.0.1", "0.0.0.0"}) {
    EXPECT_EQ(MetricsBindError(bind), "") << bind;
  }
  for (const char* bind : {"::1", "::"}) {
    if (MetricsSupportIpv6()) {
      EXPECT_EQ(MetricsBindError(bind), "") << bind;
    } else {
      EXPECT_NE(MetricsBindError(bind).find("has no IPv6"), std::string::npos)
          << bind << ": " << MetricsBindError(bind);
    }
  }
}

TEST(ConfigTest, EmptyTlsFilesAreRefusedNotReadAsPlaintext) {
  // Before: `--tls-cert '' --tls-key ''` started a plaintext server.
  for (const char* flag : {"--tls-cert", "--tls-key", "--tls-client-ca"}) {
    CLI::App app;
    ServerConfig c;
    AddServerFlags(app, &c);
    try {
      app.parse(std::vector<std::string>{"", flag});  // reversed: last first
      ADD_FAILURE() << flag << " '' was accepted";
    } catch (const CLI::ValidationError& e) {
      EXPECT_NE(std::string(e.what()).find("is empty"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(flag), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace dot::server
