// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-server's flags land in their option structs, in the units they say.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include "config.h"

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

}  // namespace
}  // namespace dot::server
