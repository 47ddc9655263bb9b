// SPDX-License-Identifier: AGPL-3.0-or-later
#include "remote_calls.h"

#include <dlfcn.h>
#include <unistd.h>

#include <mutex>
#include <string>
#include <vector>

// The module's entry, when a build links the remote half into dotctl
// (sanitizer builds, client/CMakeLists.txt); null otherwise.
extern "C" const dot::client::RemoteCalls* dot_client_remote_calls(
    const char* key, size_t table_size) __attribute__((weak));

namespace dot::client {
namespace {

// The directory of this executable ("" when /proc is not mounted).
std::string ExecutableDirectory() {
  std::string path(4096, '\0');
  const ssize_t n = ::readlink("/proc/self/exe", path.data(), path.size());
  if (n <= 0 || static_cast<size_t>(n) >= path.size()) return "";
  path.resize(static_cast<size_t>(n));
  return path.substr(0, path.rfind('/') + 1);
}

struct Loaded {
  const RemoteCalls* calls = nullptr;
  std::string error;
};

// Where the module may be: beside dotctl (a build tree), then where an
// install puts it relative to dotctl; without /proc, the install's
// absolute path alone (never a path relative to the working directory).
std::vector<std::string> Candidates() {
  const std::string dir = ExecutableDirectory();
  if (dir.empty()) {
    return {std::string(DOT_REMOTE_MODULE_FULL_DIR "/") + kRemoteModuleFile};
  }
  return {dir + kRemoteModuleFile,
          dir + DOT_REMOTE_MODULE_DIR "/" + kRemoteModuleFile};
}

Loaded Load() {
  Loaded out;
  if (dot_client_remote_calls != nullptr) {  // linked in
    out.calls = dot_client_remote_calls(DOT_REMOTE_ABI, sizeof(RemoteCalls));
    if (out.calls == nullptr) {
      out.error = "the remote half linked into dotctl refused its key " +
                  std::string(DOT_REMOTE_ABI);
    }
    return out;
  }
  const std::vector<std::string> candidates = Candidates();
  for (const std::string& file : candidates) {
    if (::access(file.c_str(), F_OK) != 0) continue;
    // RTLD_NOW: a module that does not fit this dotctl fails here, whole,
    // not at its first call.
    void* module = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (module == nullptr) {
      out.error = "cannot load " + file + ": " + ::dlerror();
      return out;
    }
    using Entry = const RemoteCalls* (*)(const char*, size_t);
    const auto entry =
        reinterpret_cast<Entry>(::dlsym(module, kRemoteModuleEntry));
    out.calls =
        entry == nullptr ? nullptr : entry(DOT_REMOTE_ABI, sizeof(RemoteCalls));
    if (out.calls == nullptr) {
      out.error = file + " is not the remote half of this dotctl (" +
                  DOT_REMOTE_ABI + "): another build; reinstall dot";
    }
    return out;  // kept loaded for the life of the process
  }
  out.error = "cannot find " + std::string(kRemoteModuleFile) + " in";
  for (size_t i = 0; i < candidates.size(); ++i) {
    out.error += (i == 0 ? " " : " or ") +
                 candidates[i].substr(0, candidates[i].rfind('/'));
  }
  out.error += " (dotctl's remote commands need it; --local does not)";
  return out;
}

}  // namespace

const RemoteCalls* LoadRemoteCalls(std::string* error) {
  static std::once_flag once;
  static Loaded loaded;
  std::call_once(once, [] { loaded = Load(); });
  if (loaded.calls == nullptr) *error = loaded.error;
  return loaded.calls;
}

}  // namespace dot::client
