// SPDX-License-Identifier: AGPL-3.0-or-later
// The oracle the wire fuzz targets share: a failure aborts with its reason
// (libFuzzer keeps the input), and a refusal must be an honest one.
#ifndef DOT_TESTS_FUZZ_WIRE_ORACLE_H_
#define DOT_TESTS_FUZZ_WIRE_ORACLE_H_

#include <cstdio>
#include <cstdlib>
#include <string>

#include "dot/status.h"
#include "wire/wire.h"

namespace dot::fuzz {

[[noreturn]] inline void Fail(const std::string& what) {
  std::fprintf(stderr, "ORACLE FAILED: %s\n", what.c_str());
  std::abort();
}

// A refusal is a non-OK status with a message, never sent as gRPC OK
// (except kNoTriangulation, an answer, where `no_triangulation_is_ok`).
inline void CheckRefusal(const Status& s, bool no_triangulation_is_ok) {
  if (s.ok()) Fail("refusal with an OK status");
  if (s.message.empty()) Fail("refusal without a message");
  if (wire::ToGrpcStatus(s).ok() &&
      !(no_triangulation_is_ok && s.code == StatusCode::kNoTriangulation)) {
    Fail("failure " + std::string(StatusCodeName(s.code)) + " sent as gRPC OK");
  }
}

}  // namespace dot::fuzz

#endif  // DOT_TESTS_FUZZ_WIRE_ORACLE_H_
