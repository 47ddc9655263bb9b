// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl's exit codes, for scripts and container health checks.
#ifndef DOT_CLIENT_EXIT_CODES_H_
#define DOT_CLIENT_EXIT_CODES_H_

namespace dot::client {

enum ExitCode : int {
  kExitOk = 0,
  kExitFailed = 1,           // a request failed, or the server is NOT_SERVING
  kExitUsage = 2,            // bad flags or unreadable input
  kExitUnavailable = 3,      // the server could not be reached
  kExitNoTriangulation = 4,  // some polygon has no triangulation
  kExitPartial = 5,          // a fill stopped early; what it did is written
};

}  // namespace dot::client

#endif  // DOT_CLIENT_EXIT_CODES_H_
