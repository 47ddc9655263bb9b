// SPDX-License-Identifier: AGPL-3.0-or-later
// Stable names of status codes (CLI, logs, the wire).
#include "dot/status.h"

namespace dot {

std::string_view StatusCodeName(StatusCode c) {
  switch (c) {
    case StatusCode::kOk:
      return "ok";
    case StatusCode::kNoTriangulation:
      return "no_triangulation";
    case StatusCode::kInvalidArgument:
      return "invalid_argument";
    case StatusCode::kResourceExhausted:
      return "resource_exhausted";
    case StatusCode::kCancelled:
      return "cancelled";
    case StatusCode::kDeadlineExceeded:
      return "deadline_exceeded";
    case StatusCode::kInternal:
      return "internal";
  }
  return "?";
}

}  // namespace dot
