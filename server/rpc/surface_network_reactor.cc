// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/surface_network_reactor.h"

#include <chrono>

namespace dot::server {

Status SurfaceNetworkUse::Run(Call& call, Input network, Job& job,
                              const Control& control,
                              const Progress& progress) {
  return call.Run(
      std::move(network), control,
      [&](int done, int total) {
        // The first report and the last patch are always sent.
        progress(done == 0 || done == total, [&](Response* m) {
          v1::SurfaceProgress* p = m->mutable_progress();
          p->set_patches_done(static_cast<uint32_t>(done));
          p->set_patches_total(static_cast<uint32_t>(total));
          p->set_elapsed_ms(std::chrono::duration<double, std::milli>(
                                Clock::now() - job.arrived)
                                .count());
        });
      },
      &job.log_detail);
}

}  // namespace dot::server
