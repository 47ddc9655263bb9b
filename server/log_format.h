// SPDX-License-Identifier: AGPL-3.0-or-later
// The server's log lines: text ("2026-11-28T06:55:01.123Z info message") or
// JSON, one object a line ({"time":...,"level":...,"message":...}, the
// message escaped), for log collectors. Times in UTC either way.
#ifndef DOT_SERVER_LOG_FORMAT_H_
#define DOT_SERVER_LOG_FORMAT_H_

namespace dot::server {

// Sets spdlog's default logger's format.
void SetLogFormat(bool json);

}  // namespace dot::server

#endif  // DOT_SERVER_LOG_FORMAT_H_
