// SPDX-License-Identifier: AGPL-3.0-or-later
#include "log_format.h"

#include <spdlog/pattern_formatter.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <string>
#include <string_view>

#include "wire/json_text.h"

namespace dot::server {
namespace {

// %* in a pattern: the message as the inside of a JSON string.
class JsonMessage : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&,
              spdlog::memory_buf_t& dest) override {
    // Every byte past ASCII escaped too: a message may hold a path that is
    // not UTF-8, and the line must stay valid JSON.
    const std::string out = wire::JsonEscape(
        std::string_view(msg.payload.data(), msg.payload.size()),
        /*ascii_only=*/true);
    dest.append(out.data(), out.data() + out.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<JsonMessage>();
  }
};

}  // namespace

void SetLogFormat(bool json) {
  auto formatter = std::make_unique<spdlog::pattern_formatter>(
      spdlog::pattern_time_type::utc);
  if (json) {
    formatter->add_flag<JsonMessage>('*').set_pattern(
        R"({"time":"%Y-%m-%dT%H:%M:%S.%eZ","level":"%l","message":"%*"})");
  } else {
    formatter->set_pattern("%Y-%m-%dT%H:%M:%S.%eZ %^%l%$ %v");
  }
  spdlog::set_formatter(std::move(formatter));
}

}  // namespace dot::server
