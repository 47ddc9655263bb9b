// SPDX-License-Identifier: AGPL-3.0-or-later
// The dot-server binary itself: SIGTERM finishes in-flight work and exits 0.
#include <arpa/inet.h>
#include <fcntl.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <future>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "fixtures/service_fixture.h"
#include "remote/grpc_calls.h"

extern char** environ;

namespace dot {
namespace {

// Starts args[0] with `args`, stdin from `stdin_fd` when >= 0, stdout and
// stderr to the file `output` when given; its pid, or -1 when it could not
// be started.
pid_t Spawn(std::vector<std::string> args, int stdin_fd = -1,
            const std::string& output = "") {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdin_fd >= 0) {
    posix_spawn_file_actions_adddup2(&actions, stdin_fd, STDIN_FILENO);
  }
  if (!output.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  pid_t pid = -1;
  if (::posix_spawn(&pid, args[0].c_str(), &actions, nullptr, argv.data(),
                    environ) != 0) {
    pid = -1;
  }
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

TEST(ServerProcessTest, SigtermDrainsInFlightWorkAndExitsZero) {
  const std::string address =
      "127.0.0.1:" + std::to_string(testing::FreeLoopbackPort());
  std::vector<std::string> args = {DOT_SERVER_PATH,
                                   "--listen",
                                   address,
                                   "--metrics-port",
                                   "0",
                                   "--source-archive",
                                   "",
                                   "--log-level",
                                   "warn",
                                   "--threads",
                                   "1"};
  const pid_t pid = Spawn(args);
  ASSERT_GT(pid, 0);
  auto channel =
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
  ASSERT_TRUE(channel->WaitForConnected(std::chrono::system_clock::now() +
                                        std::chrono::seconds(10)));
  auto stub = v1::Triangulator::NewStub(channel);
  auto slow = testing::CurveRequest(Curve::kMoment, 1200,
                                    testing::Weights(Metric::kSquaredDihedral));
  auto in_flight = std::async(std::launch::async, [&] {
    return client::TriangulateRemote(*stub, slow,
                                     MakeCurve(Curve::kMoment, 1200), 60);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  const client::CallOutcome out = in_flight.get();
  EXPECT_TRUE(out.status.ok()) << out.status.error_message();
  EXPECT_EQ(out.summary.status(), v1::RESULT_STATUS_OK);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(ServerProcessTest, ExitWithStdinEndsWhenTheParentsPipeCloses) {
  // Before: Blender's "Run Locally" server kept listening after Blender was
  // killed (no atexit hook runs). Now the parent holds a pipe to its stdin.
  const std::string address =
      "127.0.0.1:" + std::to_string(testing::FreeLoopbackPort());
  std::vector<std::string> args = {DOT_SERVER_PATH,
                                   "--listen",
                                   address,
                                   "--metrics-port",
                                   "0",
                                   "--log-level",
                                   "warn",
                                   "--exit-with-stdin"};
  int pipe_fds[2];
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);  // the child gets only stdin
  const pid_t pid = Spawn(args, pipe_fds[0]);
  ASSERT_GT(pid, 0);
  ::close(pipe_fds[0]);
  auto channel =
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
  ASSERT_TRUE(channel->WaitForConnected(std::chrono::system_clock::now() +
                                        std::chrono::seconds(10)));
  ::close(pipe_fds[1]);  // the parent is gone
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);  // it exits by itself
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

// --log-format json: every line one object (time in UTC, level, message),
// for log collectors; text lines carry the same UTC time.
TEST(ServerProcessTest, LogFormatJsonIsOneObjectALine) {
  for (const std::string format : {"json", "text"}) {
    SCOPED_TRACE(format);
    const std::string log =
        ::testing::TempDir() + "dot-server-log-" + format + ".txt";
    const std::string address =
        "127.0.0.1:" + std::to_string(testing::FreeLoopbackPort());
    std::vector<std::string> args = {DOT_SERVER_PATH,
                                     "--listen",
                                     address,
                                     "--metrics-port",
                                     "0",
                                     "--log-format",
                                     format,
                                     "--drain-seconds",
                                     "1"};
    const pid_t pid = Spawn(args, -1, log);
    ASSERT_GT(pid, 0);
    auto channel =
        grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
    ASSERT_TRUE(channel->WaitForConnected(std::chrono::system_clock::now() +
                                          std::chrono::seconds(10)));
    ::kill(pid, SIGTERM);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    std::ifstream in(log);
    std::string line;
    int lines = 0;
    const std::regex json(
        R"re(\{"time":"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z","level":"(info|warning|error)","message":"([^"\\]|\\.)*"\})re");
    const std::regex text(
        R"re(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z \S+ .*)re");
    while (std::getline(in, line)) {
      ++lines;
      EXPECT_TRUE(std::regex_match(line, format == "json" ? json : text))
          << line;
    }
    EXPECT_GE(lines, 2);  // listening, then shutting down
  }
}

TEST(ServerProcessTest, ProgressIsStreamedForLongRuns) {
  auto s = testing::StartServer(testing::LoopbackConfig());
  auto request = testing::CurveRequest(
      Curve::kTwist, 1501, testing::Weights(Metric::kSquaredDihedral));
  request.mutable_options()->set_progress_interval_ms(20);
  std::vector<v1::Progress> seen;
  const client::CallOutcome out = client::TriangulateRemote(
      *s.stub, request, MakeCurve(Curve::kTwist, 1501), 60,
      [&](const v1::Progress& p) { seen.push_back(p); });
  ASSERT_TRUE(out.status.ok()) << out.status.error_message();
  ASSERT_GE(seen.size(), 2u);
  for (size_t i = 1; i < seen.size(); ++i) {
    EXPECT_GE(seen[i].elapsed_ms(), seen[i - 1].elapsed_ms());
    EXPECT_GE(seen[i].stage(), seen[i - 1].stage());
  }
}

// Out of file descriptors, gRPC 1.51 stops accepting for good; the server
// must not live on deaf: its listener watchdog makes it drain and exit 70
// for a supervisor to restart it.
TEST(ServerProcessTest, ListenerThatStopsAcceptingExitsNonZero) {
  const int port = testing::FreeLoopbackPort();
  const std::string address = "127.0.0.1:" + std::to_string(port);
  std::vector<std::string> args = {"/usr/bin/prlimit",
                                   "--nofile=128:128",
                                   DOT_SERVER_PATH,
                                   "--listen",
                                   address,
                                   "--metrics-port",
                                   "0",
                                   "--log-level",
                                   "error",
                                   "--listener-patience-s",
                                   "2"};
  const pid_t pid = Spawn(args);
  ASSERT_GT(pid, 0);
  auto channel =
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
  ASSERT_TRUE(channel->WaitForConnected(std::chrono::system_clock::now() +
                                        std::chrono::seconds(20)));
  // Connections that never speak HTTP/2 use up the server's descriptors.
  std::vector<int> idle;
  for (int i = 0; i < 200; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) {
      idle.push_back(fd);
    } else {
      ::close(fd);
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  for (int fd : idle) ::close(fd);
  int status = 0;
  pid_t ended = 0;
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while ((ended = ::waitpid(pid, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (ended == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    FAIL() << "the server lived on without accepting connections";
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 70);
}

}  // namespace
}  // namespace dot
