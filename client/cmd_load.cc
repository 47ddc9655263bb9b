// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl load : a bounded load test (request count and duration both cap
// it), closed-loop or at a target rate, reporting throughput, latency
// percentiles and errors by status code.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <iostream>
#include <map>
#include <mutex>
#include <random>
#include <thread>

#include "commands.h"
#include "exit_codes.h"
#include "fill_call.h"
#include "remote_call.h"
#include "wire/wire.h"

namespace dot::client {
namespace {
using Clock = std::chrono::steady_clock;

struct LoadFlags {
  int concurrency = 4, requests = 200, channels = 1;
  double duration_s = 60, rate = 0;
  std::string curve = "monkey";
  int n = 100;
  std::vector<std::string> files;
  std::vector<std::string> meshes;  // FillHoles calls with these meshes
  RequestFlags request;
  bool json = false, local = false, batch = false;
  bool same_polygon = false;
  uint64_t seed = 0;  // 0: a random one
};

void AddLoadFlags(CLI::App* cmd, LoadFlags* f) {
  cmd->add_option("-c,--concurrency", f->concurrency, "requests in flight")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("-r,--requests", f->requests, "total requests")
      ->check(CLI::Range(1, 10000000))
      ->capture_default_str();
  cmd->add_option("-d,--duration", f->duration_s,
                  "stop after this many seconds")
      ->check(CLI::Range(0.1, 86400.0))
      ->capture_default_str();
  cmd->add_option("--rate", f->rate,
                  "target requests per second (0: as fast as answered)")
      ->capture_default_str();
  cmd->add_option("--channels", f->channels,
                  "separate connections to spread the calls over")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--curve", f->curve,
                  "built-in polygon: monkey, mobius, spiral, moment, twist")
      ->capture_default_str();
  cmd->add_option("-n,--vertices", f->n, "vertices of the built-in polygon")
      ->check(CLI::Range(3, 10000000))
      ->capture_default_str();
  cmd->add_option("--files", f->files, "use these polygon files instead");
  cmd->add_option("--meshes", f->meshes,
                  "load-test FillHoles instead: each request fills one of "
                  "these meshes (files or directories of .off, .obj, .ply, "
                  ".stl), in turn, with the default options")
      ->excludes("--files");
  cmd->add_flag("--same-polygon", f->same_polygon,
                "send the polygons as they are, every time: after the first "
                "call the server's search-space cache serves them (see "
                "--no-cache); by default each request is a randomly rotated "
                "copy, so the cache cannot");
  cmd->add_option("--seed", f->seed,
                  "seed of the rotations (default: a random one, printed in "
                  "the report; the same seed repeats the same polygons, "
                  "which a second run then finds in the cache)");
  cmd->add_flag("--json", f->json, "print the report as JSON");
  cmd->add_flag("--local", f->local,
                "call the core in-process (the baseline for overhead)");
  cmd->add_flag("--batch", f->batch,
                "send over TriangulateBatch streams (one per --channels) "
                "keeping --concurrency requests in flight, instead of one "
                "call per polygon")
      ->excludes("--local")
      ->excludes("--rate")
      ->excludes("--meshes");
  AddRequestFlags(cmd, &f->request);
}

// The polygons to send: the files given, or one built-in curve.
bool LoadPolygons(const LoadFlags& f, std::vector<PolygonData>* polygons,
                  std::vector<PolygonSoup>* meshes, std::string* error) {
  if (!f.meshes.empty()) {
    for (const std::string& file :
         ExpandInputs(f.meshes, error, {".off", ".obj", ".ply", ".stl"})) {
      PolygonSoup soup;
      const Status s = ReadPolygonSoupFile(file, &soup);
      if (!s.ok()) *error = s.message;
      meshes->push_back(std::move(soup));
    }
  } else if (!f.files.empty()) {
    for (const std::string& file : ExpandInputs(f.files, error)) {
      PolygonData p;
      const Status s = ReadPolygonInput(file, "", &p, nullptr);
      if (!s.ok()) *error = s.message;
      polygons->push_back(std::move(p));
    }
  } else if (auto curve = CurveFromName(f.curve)) {
    polygons->push_back({MakeCurve(*curve, f.n), {}});
  } else {
    *error = "unknown curve '" + f.curve + "'";
  }
  return error->empty();
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t i = static_cast<size_t>(std::ceil(p / 100 * v.size()));
  return v[std::min(v.size() - 1, i == 0 ? 0 : i - 1)];
}

// A copy of `p` turned by a random rotation about its centroid, the same
// for the same (seed, index): the same work for the server, but coordinates
// its search-space cache has not seen.
PolygonData Rotated(const PolygonData& p, uint64_t seed, int index) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull +
                      static_cast<uint64_t>(index));
  std::normal_distribution<double> normal;
  double q[4], norm = 0;
  for (double& c : q) {
    c = normal(rng);
    norm += c * c;
  }
  norm = std::sqrt(norm);
  for (double& c : q) c /= norm;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double r[3][3] = {
      {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
      {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
      {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  Vec3 c{0, 0, 0};
  for (const Vec3& v : p.vertices) {
    c.x += v.x;
    c.y += v.y;
    c.z += v.z;
  }
  const double n = p.vertices.empty() ? 1.0 : double(p.vertices.size());
  c = {c.x / n, c.y / n, c.z / n};
  const auto turn = [&](const Vec3& v) {
    return Vec3{r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z,
                r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
                r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z};
  };
  PolygonData out;
  out.vertices.reserve(p.vertices.size());
  for (const Vec3& v : p.vertices) {
    const Vec3 t = turn({v.x - c.x, v.y - c.y, v.z - c.z});
    out.vertices.push_back({t.x + c.x, t.y + c.y, t.z + c.z});
  }
  for (const Vec3& v : p.normals) out.normals.push_back(turn(v));
  return out;
}

// Outcomes by status label, and the latencies of the answered ones.
class Tally {
 public:
  void Record(const std::string& label, double ms, bool cache_hit = false,
              const std::string& error = "") {
    std::lock_guard<std::mutex> lock(mu_);
    ++by_status_[label];
    if (label == "OK" || label == "NO_TRIANGULATION") latencies_.push_back(ms);
    if (cache_hit) ++cache_hits_;
    if (!error.empty() && first_error_.count(label) == 0) {
      first_error_[label] = error;
    }
  }
  // Prints the report (unless quiet); returns the exit code.
  int Print(double seconds, const LoadFlags& flags, bool quiet) const;

 private:
  mutable std::mutex mu_;
  std::vector<double> latencies_;
  std::map<std::string, int> by_status_;
  std::map<std::string, std::string> first_error_;
  int cache_hits_ = 0;
};

int Tally::Print(double seconds, const LoadFlags& flags, bool quiet) const {
  std::lock_guard<std::mutex> lock(mu_);
  int total = 0, errors = 0, unavailable = 0;
  for (const auto& [label, count] : by_status_) {
    total += count;
    if (label != "OK" && label != "NO_TRIANGULATION") errors += count;
    if (label == "UNAVAILABLE") unavailable += count;
  }
  const auto count_of = [&](const char* label) {
    const auto it = by_status_.find(label);
    return it == by_status_.end() ? 0 : it->second;
  };
  const double throughput = latencies_.size() / seconds;
  const double p50 = Percentile(latencies_, 50),
               p90 = Percentile(latencies_, 90),
               p95 = Percentile(latencies_, 95),
               p99 = Percentile(latencies_, 99),
               max = Percentile(latencies_, 100),
               min = Percentile(latencies_, 0);
  double mean = 0;
  for (double ms : latencies_) mean += ms / latencies_.size();
  // A histogram as ghz prints one: ten buckets from min to max, each
  // named by its upper mark.
  constexpr int kBuckets = 10;
  std::vector<int> counts(latencies_.empty() ? 0 : kBuckets, 0);
  const double width = (max - min) / kBuckets;
  for (double ms : latencies_) {
    const int b = width > 0 ? static_cast<int>((ms - min) / width) : 0;
    ++counts[std::min(b, kBuckets - 1)];
  }
  auto mark = [&](int b) { return min + width * (b + 1); };
  const char* polygons = flags.same_polygon ? "same" : "rotated";
  if (flags.json) {
    std::printf(
        "{\"version\":1,\"requests\":%d,\"succeeded\":%zu,\"errors\":%d,"
        "\"seconds\":%.3f,"
        "\"throughput_rps\":%.2f,\"latency_ms\":{\"mean\":%.3f,\"min\":%.3f,"
        "\"p50\":%.3f,\"p90\":%.3f,\"p95\":%.3f,\"p99\":%.3f,\"max\":%.3f},"
        "\"histogram\":[",
        total, latencies_.size(), errors, seconds, throughput, mean, min, p50,
        p90, p95, p99, max);
    for (size_t b = 0; b < counts.size(); ++b) {
      std::printf("%s{\"mark_ms\":%.3f,\"count\":%d}", b ? "," : "",
                  mark(static_cast<int>(b)), counts[b]);
    }
    std::printf(
        "],\"call\":\"%s\",\"polygons\":\"%s\",\"seed\":%llu,"
        "\"cache_hits\":%d,\"by_status\":{",
        flags.meshes.empty() ? "Triangulate" : "FillHoles", polygons,
        static_cast<unsigned long long>(flags.seed), cache_hits_);
    bool first = true;
    for (const auto& [label, count] : by_status_) {
      std::printf("%s\"%s\":%d", first ? "" : ",", label.c_str(), count);
      first = false;
    }
    std::printf("}}\n");
  } else if (!quiet) {
    std::printf("%d requests in %.2f s, concurrency %d: %.1f req/s\n", total,
                seconds, flags.concurrency, throughput);
    std::printf(
        "latency ms: mean %.2f  min %.2f  p50 %.2f  p90 %.2f  p95 %.2f  "
        "p99 %.2f  max %.2f\n",
        mean, min, p50, p90, p95, p99, max);
    const int most =
        counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
    for (size_t b = 0; b < counts.size(); ++b) {
      std::printf("  %10.2f [%d]\t|%s\n", mark(static_cast<int>(b)), counts[b],
                  std::string(most ? 40 * counts[b] / most : 0, '#').c_str());
    }
    if (!flags.meshes.empty()) {
      std::printf("FillHoles: each request fills the next mesh given\n");
    } else if (flags.same_polygon) {
      std::printf(
          "polygons: the same %s every request (--same-polygon); search "
          "space from the server's cache in %d of %zu answers%s\n",
          flags.files.size() > 1 ? "ones" : "one", cache_hits_,
          latencies_.size(),
          flags.request.no_cache ? "" : ": add --no-cache to measure compute");
    } else {
      std::printf(
          "polygons: each request a randomly rotated copy (seed %llu), so "
          "the server's search-space cache cannot serve it (%d cache hits)\n",
          static_cast<unsigned long long>(flags.seed), cache_hits_);
    }
    for (const auto& [label, count] : by_status_) {
      std::printf("  %-20s %d\n", label.c_str(), count);
    }
  }
  std::fflush(stdout);
  for (const auto& [label, message] : first_error_) {
    std::cerr << "dotctl: " << count_of(label.c_str()) << " requests failed "
              << label << ", the first with: " << message << "\n";
  }
  if (errors > 0) {
    return latencies_.empty() && unavailable == errors ? kExitUnavailable
                                                       : kExitFailed;
  }
  return count_of("NO_TRIANGULATION") > 0 ? kExitNoTriangulation : kExitOk;
}

// What every worker of one run shares.
struct LoadRun {
  LoadRun(const LoadFlags& f, const Context& c) : flags(f), ctx(c) {}
  const LoadFlags& flags;
  const Context& ctx;
  std::vector<PolygonData> polygons;
  std::vector<PolygonSoup> meshes;               // --meshes
  std::vector<v1::TriangulateRequest> requests;  // as they are
  std::vector<Connection> servers;               // remote only
  std::unique_ptr<DelaunayHelperPool> helpers;   // local only
  double timeout_s = 0;
  Clock::time_point start, end;
  std::atomic<int> next{0};  // the next request to send
  Tally tally;

  // Claims the next request index; -1 when the run is over.
  int Claim() {
    const int i = next++;
    return i < flags.requests && Clock::now() < end ? i : -1;
  }
  // Request i, and its vertices: the polygon as it is with --same-polygon,
  // else a rotated copy.
  v1::TriangulateRequest RequestFor(int i, std::vector<Vec3>* input) const {
    const size_t k = static_cast<size_t>(i) % polygons.size();
    if (flags.same_polygon) {
      *input = polygons[k].vertices;
      return requests[k];
    }
    const PolygonData p = Rotated(polygons[k], flags.seed, i);
    *input = p.vertices;
    return wire::MakeRequest(requests[k].id(), p, flags.request.weights,
                             flags.request.ToOptions());
  }
};

// The connection worker w calls over (remote runs only).
const Connection& Server(const LoadRun& run, int w) {
  return run.servers[static_cast<size_t>(w) % run.servers.size()];
}

std::string OutcomeLabel(const CallOutcome& out) {
  if (out.status.ok() && out.summary.status() != v1::RESULT_STATUS_OK) {
    return "NO_TRIANGULATION";
  }
  return std::string(wire::GrpcCodeName(out.status.error_code()));
}

// One FillHoles call with mesh i (in turn): here or on the server.
void FillWorkerCall(LoadRun& run, int w, int i) {
  const PolygonSoup& mesh =
      run.meshes[static_cast<size_t>(i) % run.meshes.size()];
  const std::string id = "load-" + std::to_string(i);
  const FillOutcome out = run.flags.local ? FillLocal(id, {}, mesh)
                                          : Server(run, w).calls->fill(
                                                Server(run, w).channel, id, {},
                                                mesh, run.timeout_s, nullptr);
  const std::string label(wire::GrpcCodeName(out.status.error_code()));
  PrintVerbose(run.ctx, "request " + std::to_string(i) + ": " + label + " in " +
                            std::to_string(out.latency_ms) + " ms");
  run.tally.Record(label, out.latency_ms, false, out.status.error_message());
}

// One call per polygon, closed-loop or paced by --rate.
void CallWorker(LoadRun& run, int w) {
  for (int i; (i = run.Claim()) >= 0;) {
    if (run.flags.rate > 0) {
      const auto due =
          run.start + std::chrono::microseconds(
                          static_cast<int64_t>(1e6 * i / run.flags.rate));
      if (due >= run.end) return;
      std::this_thread::sleep_until(due);
    }
    if (!run.meshes.empty()) {
      FillWorkerCall(run, w, i);
      continue;
    }
    std::vector<Vec3> input;
    const auto request = run.RequestFor(i, &input);
    const CallOutcome out =
        run.flags.local
            ? TriangulateLocal(request, run.helpers.get())
            : Server(run, w).calls->triangulate(Server(run, w).channel, request,
                                                input, run.timeout_s, nullptr);
    PrintVerbose(run.ctx,
                 "request " + std::to_string(i) + ": " + DescribeTiming(out));
    run.tally.Record(OutcomeLabel(out), out.latency_ms,
                     out.status.ok() && out.summary.cache_hit(),
                     out.status.error_message());
  }
}

// One TriangulateBatch stream: a writer thread keeps `window` requests in
// flight, this thread reads results as they finish, in any order.
void StreamWorker(LoadRun& run, int s, int window) {
  std::mutex m;
  std::condition_variable cv;
  int in_flight = 0;
  bool closed = false;
  std::map<std::string, Clock::time_point> sent;
  v1::TriangulateRequest request;  // the one being written
  const auto next = [&]() -> const v1::TriangulateRequest* {
    {
      std::unique_lock<std::mutex> lock(m);
      cv.wait(lock, [&] { return closed || in_flight < window; });
      if (closed) return nullptr;
    }
    const int i = run.Claim();
    if (i < 0) return nullptr;
    std::vector<Vec3> input;
    request = run.RequestFor(i, &input);
    request.set_id(std::to_string(i));
    std::lock_guard<std::mutex> lock(m);
    sent[request.id()] = Clock::now();
    ++in_flight;
    return &request;
  };
  int answered = 0;
  const auto on_answer = [&](const v1::TriangulateResponse& msg) {
    if (!msg.has_summary() && !msg.has_error()) return;
    ++answered;
    const std::string label =
        msg.has_error()
            ? std::string(wire::GrpcCodeName(
                  static_cast<grpc::StatusCode>(msg.error().code())))
        : msg.summary().status() == v1::RESULT_STATUS_OK ? "OK"
                                                         : "NO_TRIANGULATION";
    Clock::time_point t0;
    {
      std::lock_guard<std::mutex> lock(m);
      t0 = sent[msg.id()];
      sent.erase(msg.id());
      --in_flight;
    }
    cv.notify_one();
    const double ms = MsSince(t0);
    PrintVerbose(run.ctx, "request " + msg.id() + ": " + label + " in " +
                              std::to_string(ms) + " ms");
    run.tally.Record(label, ms, msg.has_summary() && msg.summary().cache_hit(),
                     msg.has_error() ? msg.error().message() : "");
  };
  const auto reads_done = [&] {
    {
      std::lock_guard<std::mutex> lock(m);
      closed = true;
    }
    cv.notify_one();
  };
  const Connection& server = run.servers[s];
  const grpc::Status status = server.calls->batch(
      server.channel,
      std::chrono::system_clock::now() + (run.end - Clock::now()) +
          std::chrono::milliseconds(static_cast<int64_t>(run.timeout_s * 1000)),
      next, on_answer, reads_done);
  if (!status.ok() && sent.empty() && answered == 0) {
    // The stream failed before it carried a request: that is one failure.
    run.tally.Record(std::string(wire::GrpcCodeName(status.error_code())), 0,
                     false, status.error_message());
  }
  // Requests still unanswered failed with the stream.
  const std::string lost(wire::GrpcCodeName(
      status.ok() ? grpc::StatusCode::DATA_LOSS : status.error_code()));
  for (size_t k = 0; k < sent.size(); ++k) {
    run.tally.Record(lost, 0, false,
                     status.ok() ? "the stream ended without an answer"
                                 : status.error_message());
  }
}

void RunLoad(LoadFlags& f, Context* ctx) {
  while (f.seed == 0) f.seed = std::random_device{}();
  LoadRun run(f, *ctx);
  std::string error;
  if (!LoadPolygons(f, &run.polygons, &run.meshes, &error)) {
    PrintError(error);
    RaiseExitCode(ctx, kExitUsage);
    return;
  }
  for (size_t i = 0; i < run.polygons.size(); ++i) {
    run.requests.push_back(wire::MakeRequest("load-" + std::to_string(i),
                                             run.polygons[i], f.request.weights,
                                             f.request.ToOptions()));
  }
  if (f.local && f.request.delaunay == "tetgen") {
    run.helpers = LocalDelaunayHelpers(f.concurrency);
  }
  for (int c = 0; c < f.channels && !f.local; ++c) {
    run.servers.push_back(ConnectOrReport(ctx, f.json));
    if (!run.servers.back()) return;
  }
  run.timeout_s = ctx->connection.timeout_s;
  run.start = Clock::now();
  run.end = run.start + std::chrono::milliseconds(
                            static_cast<int64_t>(f.duration_s * 1000));
  std::vector<std::thread> threads;
  if (f.batch) {
    const int streams = static_cast<int>(run.servers.size());
    for (int s = 0; s < streams; ++s) {
      const int window = (f.concurrency + streams - 1 - s) / streams;
      if (window > 0) {
        threads.emplace_back(
            [&run, s, window] { StreamWorker(run, s, window); });
      }
    }
  } else {
    for (int w = 0; w < f.concurrency; ++w) {
      threads.emplace_back([&run, w] { CallWorker(run, w); });
    }
  }
  for (auto& t : threads) t.join();
  const double seconds =
      std::chrono::duration<double>(Clock::now() - run.start).count();
  RaiseExitCode(ctx, run.tally.Print(seconds, f, ctx->quiet));
}

}  // namespace

void AddLoadCommand(CLI::App& app, Context* ctx) {
  auto flags = std::make_shared<LoadFlags>();
  CLI::App* cmd = app.add_subcommand(
      "load",
      "Load-test a server: --requests and --duration both bound the run.\n"
      "Example: dotctl load --concurrency 8 --requests 1000 --curve monkey "
      "-n 2000");
  AddLoadFlags(cmd, flags.get());
  cmd->callback([flags, ctx] { RunLoad(*flags, ctx); });
}

}  // namespace dot::client
