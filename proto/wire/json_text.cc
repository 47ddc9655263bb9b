// SPDX-License-Identifier: AGPL-3.0-or-later
#include "wire/json_text.h"

#include <cstdio>

namespace dot::wire {

std::string JsonEscape(std::string_view text, bool ascii_only) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (byte < 0x20 || (ascii_only && byte >= 0x80)) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", byte);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

}  // namespace dot::wire
