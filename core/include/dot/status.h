// SPDX-License-Identifier: AGPL-3.0-or-later
// Outcome of a library call: a code and a message that names the problem.
#ifndef DOT_STATUS_H_
#define DOT_STATUS_H_

#include <string>
#include <string_view>
#include <utility>

namespace dot {

enum class StatusCode {
  kOk,
  kNoTriangulation,    // a normal answer: no triangulation in the space
  kInvalidArgument,    // the input is malformed (message names index/value)
  kResourceExhausted,  // over a size or memory limit
  kCancelled,
  kDeadlineExceeded,
  kInternal,  // a backend failed (e.g. TetGen raised an error)
};

std::string_view StatusCodeName(StatusCode c);

struct Status {
  StatusCode code = StatusCode::kOk;
  std::string message;
  bool ok() const { return code == StatusCode::kOk; }
};

inline Status OkStatus() { return {}; }
inline Status MakeStatus(StatusCode code, std::string message) {
  return {code, std::move(message)};
}
// The common failure: the input is malformed; `message` names what and where.
inline Status InvalidArgument(std::string message) {
  return {StatusCode::kInvalidArgument, std::move(message)};
}

}  // namespace dot

#endif  // DOT_STATUS_H_
