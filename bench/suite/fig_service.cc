// SPDX-License-Identifier: AGPL-3.0-or-later
// The service on loopback: dot-server and `dotctl load` against the same
// load run in-process (`dotctl load --local`), for small, medium and large
// polygons at several concurrencies. Requests skip the server's cache
// (--no-cache) so both sides do the same work. Server and client share the
// machine's cores, as they would on one node.
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <thread>

#include "measure.h"
#include "plot.h"
#include "process.h"
#include "suite.h"

extern char** environ;

namespace dot::bench {
namespace {

struct LoadResult {
  double rps = NAN, p50 = NAN, p99 = NAN;
  double cpu_ms_per_call = NAN;  // of the process that solved
  int errors = 0;
};

double Seconds(const timeval& t) { return t.tv_sec + t.tv_usec * 1e-6; }

// CPU seconds (user + system) the server process has used so far.
double ProcessCpuSeconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), {});
  const size_t close = stat.rfind(')');
  if (close == std::string::npos) return NAN;
  std::istringstream fields(stat.substr(close + 2));
  std::string f;
  double utime = 0, stime = 0;
  for (int i = 3; i <= 15 && fields >> f; ++i) {
    if (i == 14) utime = std::strtod(f.c_str(), nullptr);
    if (i == 15) stime = std::strtod(f.c_str(), nullptr);
  }
  return (utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

// CPU seconds used by reaped children (the in-process `dotctl load`).
double ChildrenCpuSeconds() {
  rusage u{};
  ::getrusage(RUSAGE_CHILDREN, &u);
  return Seconds(u.ru_utime) + Seconds(u.ru_stime);
}

// `dotctl <global> load <mode> ...`: global is "-s address" for the server
// `server`, mode is "--local" for in-process (server 0). CPU per call is the
// server's, or the in-process client's.
LoadResult Load(const std::string& dotctl, const std::string& global,
                const std::string& mode, int n, int concurrency, int requests,
                int reps, pid_t server) {
  std::vector<double> rps, p50, p99, cpu;
  LoadResult out;
  for (int r = 0; r < reps; ++r) {
    const double cpu0 =
        server > 0 ? ProcessCpuSeconds(server) : ChildrenCpuSeconds();
    const std::string json =
        RunCapture(dotctl + " " + global + " load " + mode +
                   " --json --no-cache --curve monkey -n " + std::to_string(n) +
                   " -c " + std::to_string(concurrency) + " -r " +
                   std::to_string(requests) + " -d 60");
    const double cpu1 =
        server > 0 ? ProcessCpuSeconds(server) : ChildrenCpuSeconds();
    cpu.push_back((cpu1 - cpu0) * 1000 / requests);
    rps.push_back(JsonNumber(json, "throughput_rps"));
    p50.push_back(JsonNumber(json, "p50"));
    p99.push_back(JsonNumber(json, "p99"));
    out.errors += static_cast<int>(JsonNumber(json, "errors"));
  }
  out.rps = Median(rps);
  out.p50 = Median(p50);
  out.p99 = Median(p99);
  out.cpu_ms_per_call = Median(cpu);
  return out;
}

}  // namespace

void RunService(const Config& config, std::ostream& report) {
  report << "## Service on loopback\n\n";
  const int port = FreeLoopbackPort();
  const std::string address = "127.0.0.1:" + std::to_string(port);
  const std::string listen = "--listen=" + address;
  std::vector<std::string> args = {config.server_path, listen,
                                   "--metrics-port=0", "--log-level=warn"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (port == 0 || ::posix_spawn(&pid, config.server_path.c_str(), nullptr,
                                 nullptr, argv.data(), environ) != 0) {
    report << "Could not start `" << config.server_path << "`.\n\n";
    return;
  }
  const std::string dotctl = config.dotctl_path;
  bool up = false;
  for (int i = 0; i < 100 && !up; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    up = std::system(
             (dotctl + " -s " + address + " health >/dev/null 2>&1").c_str()) ==
         0;
  }
  struct Case {
    int n, requests;
    std::vector<int> concurrency;
  };
  const std::vector<Case> cases =
      config.quick ? std::vector<Case>{{100, 200, {1, 4}}, {2000, 10, {2}}}
                   : std::vector<Case>{{100, 3000, {1, 2, 4, 16}},
                                       {2000, 150, {1, 2, 4}},
                                       {20000, 12, {1, 2}}};
  const int reps = config.quick ? 1 : config.reps;
  std::ofstream csv(config.Path("service.csv"));
  csv << "n,concurrency,mode,throughput_rps,p50_ms,p99_ms,cpu_ms_per_call,"
         "errors\n";
  report << "`dotctl load` against `dot-server` (2 compute threads) on "
            "127.0.0.1, one call per polygon and over TriangulateBatch "
            "streams (`--batch`), and the same load in-process (`--local`); "
            "median of "
         << reps
         << " runs each. CPU per call: the server process's user + system "
            "time (`/proc/PID/stat`) over the run, against the in-process "
            "client's (its rusage). Data: `service.csv`.\n\n"
         << "| n | concurrency | in-process req/s | server req/s (ratio) | "
            "batch req/s (ratio) | in-process p50 / p99 ms | server p50 / p99 "
            "ms | CPU ms/call: in-process / server (ratio) / batch (ratio) | "
            "errors |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Case& c : cases) {
    for (int conc : c.concurrency) {
      std::cerr << "service: n=" << c.n << " c=" << conc << "\n";
      const std::string server = "-s " + address;
      const LoadResult local =
          Load(dotctl, "", "--local", c.n, conc, c.requests, reps, 0);
      const LoadResult remote =
          up ? Load(dotctl, server, "", c.n, conc, c.requests, reps, pid)
             : LoadResult{};
      const LoadResult batch =
          up ? Load(dotctl, server, "--batch", c.n, conc, c.requests, reps, pid)
             : LoadResult{};
      for (const auto& [mode, r] :
           {std::pair{"in-process", local}, std::pair{"server", remote},
            std::pair{"server-batch", batch}}) {
        csv << c.n << "," << conc << "," << mode << "," << r.rps << "," << r.p50
            << "," << r.p99 << "," << r.cpu_ms_per_call << "," << r.errors
            << "\n";
      }
      report << "| " << c.n << " | " << conc << " | " << Fixed(local.rps)
             << " | " << Fixed(remote.rps) << " ("
             << Fixed(remote.rps / local.rps, 2) << ") | " << Fixed(batch.rps)
             << " (" << Fixed(batch.rps / local.rps, 2) << ") | "
             << Fixed(local.p50) << " / " << Fixed(local.p99) << " | "
             << Fixed(remote.p50) << " / " << Fixed(remote.p99) << " | "
             << Fixed(local.cpu_ms_per_call, 3) << " / "
             << Fixed(remote.cpu_ms_per_call, 3) << " ("
             << Fixed(remote.cpu_ms_per_call / local.cpu_ms_per_call, 2)
             << ") / " << Fixed(batch.cpu_ms_per_call, 3) << " ("
             << Fixed(batch.cpu_ms_per_call / local.cpu_ms_per_call, 2)
             << ") | " << remote.errors + batch.errors << " |\n";
    }
  }
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  report << "\n";
}

}  // namespace dot::bench
