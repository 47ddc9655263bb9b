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
#include <thread>

#include "commands.h"
#include "exit_codes.h"
#include "remote_call.h"
#include "wire/wire.h"

namespace dot::client {
namespace {
using Clock = std::chrono::steady_clock;

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t i = static_cast<size_t>(std::ceil(p / 100 * v.size()));
  return v[std::min(v.size() - 1, i == 0 ? 0 : i - 1)];
}
}  // namespace

void AddLoadCommand(CLI::App& app, Context* ctx) {
  struct Flags {
    int concurrency = 4, requests = 200, channels = 1;
    double duration_s = 60, rate = 0;
    std::string curve = "monkey";
    int n = 100;
    std::vector<std::string> files;
    RequestFlags request;
    bool json = false, local = false, batch = false;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "load",
      "Load-test a server: --requests and --duration both bound the run.\n"
      "Example: dotctl load --concurrency 8 --requests 1000 --curve monkey "
      "--n 2000");
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
  cmd->add_flag("--json", f->json, "print the report as JSON");
  cmd->add_flag("--local", f->local,
                "call the core in-process (the baseline for overhead)");
  cmd->add_flag("--batch", f->batch,
                "send over TriangulateBatch streams (one per --channels) "
                "keeping --concurrency requests in flight, instead of one "
                "call per polygon")
      ->excludes("--local")
      ->excludes("--rate");
  AddRequestFlags(cmd, &f->request);
  cmd->callback([f, ctx] {
    std::vector<PolygonData> polygons;
    std::string error;
    if (!f->files.empty()) {
      for (const std::string& file : ExpandInputs(f->files, &error)) {
        PolygonData p;
        const Status s = ReadPolygonFile(file, &p);
        if (!s.ok()) error = s.message;
        polygons.push_back(std::move(p));
      }
    } else if (auto curve = CurveFromName(f->curve)) {
      polygons.push_back({MakeCurve(*curve, f->n), {}});
    } else {
      error = "unknown curve '" + f->curve + "'";
    }
    if (!error.empty()) {
      std::cerr << "dotctl: " << error << "\n";
      ctx->exit_code = kExitUsage;
      return;
    }
    std::vector<v1::TriangulateRequest> requests;
    for (size_t i = 0; i < polygons.size(); ++i) {
      requests.push_back(wire::MakeRequest("load-" + std::to_string(i),
                                           polygons[i], f->request.weights,
                                           f->request.ToOptions()));
    }
    std::vector<std::unique_ptr<v1::Triangulator::Stub>> stubs;
    for (int c = 0; c < f->channels && !f->local; ++c) {
      auto channel = ChannelOrReport(ctx);
      if (!channel) return;
      stubs.push_back(v1::Triangulator::NewStub(channel));
    }
    std::atomic<int> next{0};
    std::mutex mu;
    std::vector<double> latencies;
    std::map<std::string, int> by_status;
    const auto start = Clock::now();
    const auto end = start + std::chrono::milliseconds(
                                 static_cast<int64_t>(f->duration_s * 1000));
    auto record = [&](const std::string& label, double ms) {
      std::lock_guard<std::mutex> lock(mu);
      ++by_status[label];
      if (label == "OK" || label == "NO_TRIANGULATION") latencies.push_back(ms);
    };
    auto worker = [&](int w) {
      for (;;) {
        const int i = next++;
        if (i >= f->requests || Clock::now() >= end) return;
        if (f->rate > 0) {
          const auto due = start + std::chrono::microseconds(
                                       static_cast<int64_t>(1e6 * i / f->rate));
          if (due >= end) return;
          std::this_thread::sleep_until(due);
        }
        const auto& request = requests[i % requests.size()];
        const CallOutcome out =
            f->local ? TriangulateLocal(request)
                     : TriangulateRemote(*stubs[w % stubs.size()], request,
                                         polygons[i % polygons.size()].vertices,
                                         ctx->connection.timeout_s);
        std::string label(wire::GrpcCodeName(out.status.error_code()));
        if (out.status.ok() && out.summary.status() != v1::RESULT_STATUS_OK) {
          label = "NO_TRIANGULATION";
        }
        record(label, out.latency_ms);
      }
    };
    // One TriangulateBatch stream: a writer keeps `window` requests in
    // flight, this thread reads results as they finish, in any order.
    auto stream_worker = [&](int s, int window) {
      grpc::ClientContext context;
      const auto left = end - Clock::now();
      context.set_deadline(std::chrono::system_clock::now() + left +
                           std::chrono::milliseconds(static_cast<int64_t>(
                               ctx->connection.timeout_s * 1000)));
      auto stream = stubs[s]->TriangulateBatch(&context);
      std::mutex m;
      std::condition_variable cv;
      int in_flight = 0;
      bool closed = false;
      std::map<std::string, Clock::time_point> sent;
      std::thread writer([&] {
        for (;;) {
          {
            std::unique_lock<std::mutex> lock(m);
            cv.wait(lock, [&] { return closed || in_flight < window; });
            if (closed) break;
          }
          const int i = next++;
          if (i >= f->requests || Clock::now() >= end) break;
          v1::TriangulateRequest request = requests[i % requests.size()];
          request.set_id(std::to_string(i));
          {
            std::lock_guard<std::mutex> lock(m);
            sent[request.id()] = Clock::now();
            ++in_flight;
          }
          if (!stream->Write(request)) break;
        }
        stream->WritesDone();
      });
      v1::TriangulateResponse msg;
      while (stream->Read(&msg)) {
        if (!msg.has_summary() && !msg.has_error()) continue;
        std::string label =
            msg.has_error()
                ? std::string(wire::GrpcCodeName(
                      static_cast<grpc::StatusCode>(msg.error().code())))
            : msg.summary().status() == v1::RESULT_STATUS_OK
                ? "OK"
                : "NO_TRIANGULATION";
        Clock::time_point t0;
        {
          std::lock_guard<std::mutex> lock(m);
          t0 = sent[msg.id()];
          sent.erase(msg.id());
          --in_flight;
        }
        cv.notify_one();
        record(label,
               std::chrono::duration<double, std::milli>(Clock::now() - t0)
                   .count());
      }
      {
        std::lock_guard<std::mutex> lock(m);
        closed = true;
      }
      cv.notify_one();
      writer.join();
      const grpc::Status status = stream->Finish();
      // Requests still unanswered failed with the stream.
      for (size_t k = 0; k < sent.size(); ++k) {
        record(std::string(wire::GrpcCodeName(status.ok()
                                                  ? grpc::StatusCode::DATA_LOSS
                                                  : status.error_code())),
               0);
      }
    };
    std::vector<std::thread> threads;
    if (f->batch) {
      const int streams = static_cast<int>(stubs.size());
      for (int s = 0; s < streams; ++s) {
        const int window = (f->concurrency + streams - 1 - s) / streams;
        if (window > 0) threads.emplace_back(stream_worker, s, window);
      }
    } else {
      for (int w = 0; w < f->concurrency; ++w) threads.emplace_back(worker, w);
    }
    for (auto& t : threads) t.join();
    const double seconds =
        std::chrono::duration<double>(Clock::now() - start).count();
    int total = 0, errors = 0;
    for (const auto& [label, count] : by_status) {
      total += count;
      if (label != "OK" && label != "NO_TRIANGULATION") errors += count;
    }
    const double throughput = latencies.size() / seconds;
    if (f->json) {
      std::printf(
          "{\"requests\":%d,\"succeeded\":%zu,\"errors\":%d,\"seconds\":%.3f,"
          "\"throughput_rps\":%.2f,\"latency_ms\":{\"p50\":%.3f,\"p90\":%.3f,"
          "\"p99\":%.3f,\"max\":%.3f},\"by_status\":{",
          total, latencies.size(), errors, seconds, throughput,
          Percentile(latencies, 50), Percentile(latencies, 90),
          Percentile(latencies, 99), Percentile(latencies, 100));
      bool first = true;
      for (const auto& [label, count] : by_status) {
        std::printf("%s\"%s\":%d", first ? "" : ",", label.c_str(), count);
        first = false;
      }
      std::printf("}}\n");
    } else {
      std::printf("%d requests in %.2f s, concurrency %d: %.1f req/s\n", total,
                  seconds, f->concurrency, throughput);
      std::printf("latency ms: p50 %.2f  p90 %.2f  p99 %.2f  max %.2f\n",
                  Percentile(latencies, 50), Percentile(latencies, 90),
                  Percentile(latencies, 99), Percentile(latencies, 100));
      for (const auto& [label, count] : by_status) {
        std::printf("  %-20s %d\n", label.c_str(), count);
      }
    }
    ctx->exit_code = errors > 0 ? kExitFailed : kExitOk;
  });
}

}  // namespace dot::client
