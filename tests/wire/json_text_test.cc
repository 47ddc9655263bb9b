// SPDX-License-Identifier: AGPL-3.0-or-later
// JSON string escaping for dotctl's envelope and the server's log lines:
// valid JSON whatever bytes a file name holds.
#include "wire/json_text.h"

#include <gtest/gtest.h>

namespace dot::wire {
namespace {

TEST(JsonEscapeTest, KeepsUtf8AndReplacesOtherBytes) {
  EXPECT_EQ(JsonEscape("a\"b\\c\nd\te\x01"), "a\\\"b\\\\c\\nd\\te\\u0001");
  // Two-, three- and four-byte sequences pass as they are.
  EXPECT_EQ(JsonEscape("caf\xc3\xa9 \xe2\x82\xac \xf0\x9d\x84\x9e"),
            "caf\xc3\xa9 \xe2\x82\xac \xf0\x9d\x84\x9e");
  // Latin-1, a truncated sequence, an overlong form, a surrogate, past
  // U+10FFFF: one U+FFFD per byte that starts no well-formed sequence.
  EXPECT_EQ(JsonEscape("caf\xe9.off"), "caf\\ufffd.off");
  EXPECT_EQ(JsonEscape("x\xc3"), "x\\ufffd");
  EXPECT_EQ(JsonEscape("\xc0\xaf"), "\\ufffd\\ufffd");
  EXPECT_EQ(JsonEscape("\xed\xa0\x80"), "\\ufffd\\ufffd\\ufffd");
  EXPECT_EQ(JsonEscape("\xf4\x90\x80\x80"), "\\ufffd\\ufffd\\ufffd\\ufffd");
  EXPECT_EQ(JsonEscape("\xe2\x82"), "\\ufffd\\ufffd");
}

TEST(JsonEscapeTest, AsciiOnlyKeepsEveryByteExactly) {
  EXPECT_EQ(JsonEscape("caf\xc3\xa9", true), "caf\\u00c3\\u00a9");
  EXPECT_EQ(JsonEscape("caf\xe9", true), "caf\\u00e9");
}

}  // namespace
}  // namespace dot::wire
