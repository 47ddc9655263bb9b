// SPDX-License-Identifier: AGPL-3.0-or-later
// A dotctl-remote.so of another build, for CliRemoteModuleTest: its entry
// point refuses every key, as a module built from other sources does.
#include <cstddef>

extern "C" __attribute__((visibility("default"))) const void*
dot_client_remote_calls(const char* /*key*/, size_t /*table_size*/) {
  return nullptr;
}
