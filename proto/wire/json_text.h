// SPDX-License-Identifier: AGPL-3.0-or-later
// The inside of a JSON string: quotes, backslashes and control characters
// escaped; well-formed UTF-8 kept, and any other byte past ASCII given as
// U+FFFD, so the JSON is valid whatever the text. With `ascii_only`, every
// byte past ASCII is \u00XX instead (a path in a log line, kept exact).
// Shared by dotctl's --json envelope and the server's JSON log lines.
#ifndef DOT_PROTO_WIRE_JSON_TEXT_H_
#define DOT_PROTO_WIRE_JSON_TEXT_H_

#include <string>
#include <string_view>

namespace dot::wire {

std::string JsonEscape(std::string_view text, bool ascii_only = false);

}  // namespace dot::wire

#endif  // DOT_PROTO_WIRE_JSON_TEXT_H_
