// SPDX-License-Identifier: AGPL-3.0-or-later
// Client-chosen text in the request log: escaped, so it cannot forge lines.
#include "rpc/request_log.h"

#include <gtest/gtest.h>

namespace dot::server {
namespace {

TEST(RequestLogTest, EscapesControlCharactersQuotesAndNonAscii) {
  EXPECT_EQ(EscapeForLog("req-7_a.b"), "req-7_a.b");
  EXPECT_EQ(EscapeForLog("a\nrpc=Fake status=OK"), "a\\x0arpc=Fake status=OK");
  EXPECT_EQ(EscapeForLog("q\"b\\"), "q\\x22b\\x5c");
  EXPECT_EQ(EscapeForLog("\xc3\xa9"), "\\xc3\\xa9");
  EXPECT_EQ(EscapeForLog(std::string("a\0b", 3)), "a\\x00b");
}

TEST(RequestLogTest, CutsLongText) {
  const std::string id(1000, 'x');
  EXPECT_EQ(EscapeForLog(id, 8), "xxxxxxxx...");
  EXPECT_EQ(EscapeForLog(id).size(), 256u + 3);
}

}  // namespace
}  // namespace dot::server
