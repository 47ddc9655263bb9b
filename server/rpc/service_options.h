// SPDX-License-Identifier: AGPL-3.0-or-later
// Configuration of the dot.v1.Triangulator service: the one home of every
// setting the RPC layer reads. dot-server's flags write into these fields
// (server/config.cc); the defaults here are the documented ones.
#ifndef DOT_SERVER_RPC_SERVICE_OPTIONS_H_
#define DOT_SERVER_RPC_SERVICE_OPTIONS_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "dot/fill_holes.h"
#include "dot/triangulate.h"

namespace dot::server {

// What a FillHoles call of this size holds at its peak (upload, repair,
// topology, fill, answer): measured 2.9 GB for 10 M faces and 5 M
// vertices, so 100 bytes per vertex and 300 per face bound it.
inline int64_t FillMemoryBytes(int64_t vertices, int64_t faces) {
  return 100 * vertices + 300 * faces;
}

struct ServiceOptions {
  // Largest polygon accepted.
  // The default is what one 16 MiB request message carries (24 bytes a
  // vertex): larger values are lowered to that, with a warning.
  int max_vertices = 698880;
  // Largest mesh FillHoles accepts.
  int64_t fill_max_vertices = 5000000;
  int64_t fill_max_faces = 10000000;
  // Memory all FillHoles calls may hold at once, uploads included; each is
  // charged FillMemoryBytes() of what it has sent, before the work.
  int64_t fill_memory_bytes = int64_t{6} << 30;
  // Compute time per request; a request's time_budget_ms and the client's
  // deadline can only shorten it.
  int max_compute_ms = 60000;
  // The core options every request starts from. A request may choose its
  // search space, backend and protection, and lower (never raise)
  // `memory_budget_bytes`; `all_space_max_vertices` is the server's alone.
  Options solve;
  // Approximate size of each streamed mesh chunk.
  size_t chunk_bytes = size_t{1} << 20;
  // Largest gRPC message received or sent (reported by GetServerInfo).
  int max_message_bytes = 16 << 20;
  // Triangulate calls over the Delaunay space up to this many vertices run
  // on the RPC's own thread when a compute slot is free: no handoff. Such a
  // run cannot see a cancel before it ends (gRPC delivers OnCancel only
  // after the handler returns), so keep it small. 0: never.
  int inline_max_vertices = 500;
  // Polygons of at least this many vertices queue in the compute pool's
  // large lane with FillHoles calls (see compute/compute_pool.h): small
  // calls go first and always keep a slot of their own.
  int large_lane_min_vertices = 20000;
  // Freed memory the allocator keeps for the next requests (at most 1 GiB;
  // main() sets glibc's thresholds from it); after a request that needed
  // more, the excess is returned to the kernel. 0: glibc's defaults.
  int64_t malloc_keep_bytes = int64_t{512} << 20;
  // What GetSource serves and GetServerInfo points to (AGPL-3.0 s. 13).
  std::string source_archive = "/usr/share/dot/dot-source.tar.gz";
  std::string source_url;
};

// The one place a request's limits come from the server's: the core options
// a request runs under are `solve`'s with its memory budget lowered to what
// the request asked for (0 bytes: no ask), never raised.
inline int64_t RequestMemoryBudget(const ServiceOptions& server,
                                   uint64_t asked_bytes) {
  const auto cap = static_cast<uint64_t>(server.solve.memory_budget_bytes);
  return static_cast<int64_t>(asked_bytes > 0 ? std::min(asked_bytes, cap)
                                              : cap);
}

// A FillHoles request's options under this server: each hole's Triangulate
// runs with the server's solve options (backend, ...) over the Delaunay
// space, with the request's memory budget (RequestMemoryBudget), the
// server's all-triangles limit, and `threads` holes at once.
inline void ApplyServerLimits(const ServiceOptions& server,
                              uint64_t asked_budget_bytes, int threads,
                              FillOptions* fill) {
  fill->triangulate = server.solve;
  fill->triangulate.space = SearchSpace::kDelaunay;
  fill->triangulate.memory_budget_bytes =
      RequestMemoryBudget(server, asked_budget_bytes);
  fill->all_space_max_vertices = server.solve.all_space_max_vertices;
  fill->threads = threads;
}

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_SERVICE_OPTIONS_H_
