// SPDX-License-Identifier: AGPL-3.0-or-later
// TLS and mutual TLS on loopback, and dotctl's subcommands end to end
// against a real server.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "fixtures/dotctl_run.h"
#include "fixtures/service_fixture.h"
#include "remote_call.h"
#include "request_flags.h"

namespace dot {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;
using testing::Dotctl;
using testing::TempDir;

// A CA, a server certificate for 127.0.0.1/localhost and a client
// certificate, made with the openssl command line.
fs::path MakeCertificates() {
  const fs::path d = TempDir("tls");
  const std::string cd = "cd '" + d.string() + "' && ";
  const char* script =
      "openssl req -x509 -newkey rsa:2048 -nodes -keyout ca.key -out ca.pem "
      "-days 2 -subj /CN=dot-test-ca 2>/dev/null && "
      "openssl req -newkey rsa:2048 -nodes -keyout server.key -out server.csr "
      "-subj /CN=localhost 2>/dev/null && "
      "printf 'subjectAltName=DNS:localhost,IP:127.0.0.1' > san.ext && "
      "openssl x509 -req -in server.csr -CA ca.pem -CAkey ca.key "
      "-CAcreateserial -out server.pem -days 2 -extfile san.ext 2>/dev/null && "
      "openssl req -newkey rsa:2048 -nodes -keyout client.key -out client.csr "
      "-subj /CN=dot-test-client 2>/dev/null && "
      "openssl x509 -req -in client.csr -CA ca.pem -CAkey ca.key "
      "-CAcreateserial -out client.pem -days 2 2>/dev/null";
  EXPECT_EQ(std::system((cd + script).c_str()), 0);
  return d;
}

grpc::Status CallOver(const client::ConnectionFlags& flags) {
  std::string error;
  auto channel = client::MakeChannel(flags, &error);
  EXPECT_TRUE(channel) << error;
  auto stub = v1::Triangulator::NewStub(channel);
  const auto r = testing::CurveRequest(Curve::kMonkey, 60,
                                       testing::Weights(Metric::kArea));
  return client::TriangulateRemote(*stub, r, MakeCurve(Curve::kMonkey, 60), 5)
      .status;
}

TEST(TlsTest, TlsAndMutualTls) {
  const fs::path d = MakeCertificates();
  auto config = testing::LoopbackConfig();
  config.tls.cert = (d / "server.pem").string();
  config.tls.key = (d / "server.key").string();
  {
    auto s = testing::StartServer(config);
    client::ConnectionFlags tls;
    tls.server = s.address;
    tls.tls_ca = (d / "ca.pem").string();
    EXPECT_TRUE(CallOver(tls).ok());
    client::ConnectionFlags plain;
    plain.server = s.address;
    EXPECT_EQ(CallOver(plain).error_code(), grpc::StatusCode::UNAVAILABLE);
  }
  config.tls.client_ca = (d / "ca.pem").string();
  auto s = testing::StartServer(config);
  client::ConnectionFlags mutual;
  mutual.server = s.address;
  mutual.tls_ca = (d / "ca.pem").string();
  EXPECT_EQ(CallOver(mutual).error_code(), grpc::StatusCode::UNAVAILABLE)
      << "a client without a certificate must be refused";
  mutual.tls_cert = (d / "client.pem").string();
  mutual.tls_key = (d / "client.key").string();
  EXPECT_TRUE(CallOver(mutual).ok());
  fs::remove_all(d);
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = testing::StartServer(testing::LoopbackConfig());
    dir_ = TempDir("cli");
    flag_ = "--server " + server_.address + " ";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) { return (dir_ / name).string(); }
  testing::RunningServer server_;
  fs::path dir_;
  std::string flag_;
};

TEST_F(CliTest, TriangulateWritesMeshAndSummary) {
  ASSERT_EQ(Dotctl("generate curve mobius -n 300 -o " + Path("m.xyz")).code, 0);
  const CliRun r = Dotctl(flag_ + "triangulate " + Path("m.xyz") + " -o " +
                          Path("m.ply") + " --squared-dihedral 1 --validate");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("ok: 298 triangles, DOT2 over delaunay3d"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("intersection-free (checked)"), std::string::npos);
  std::ifstream ply(Path("m.ply"));
  std::string first;
  std::getline(ply, first);
  EXPECT_EQ(first, "ply");

  const CliRun json = Dotctl(flag_ + "triangulate " + Path("m.xyz") +
                             " --json -o " + Path("m.obj"));
  EXPECT_EQ(json.code, 0) << json.out;
  EXPECT_NE(json.out.find("\"solver\":\"DOT1\""), std::string::npos)
      << json.out;
  const CliRun local =
      Dotctl("triangulate " + Path("m.xyz") + " --local -o " + Path("l.obj"));
  EXPECT_EQ(local.code, 0) << local.out;
  std::ifstream a(Path("m.obj")), b(Path("l.obj"));
  std::string sa((std::istreambuf_iterator<char>(a)), {}),
      sb((std::istreambuf_iterator<char>(b)), {});
  EXPECT_EQ(sa, sb);  // the server and the in-process core agree
}

TEST_F(CliTest, ExitCodes) {
  ASSERT_EQ(Dotctl("generate curve trefoil -n 90 -o " + Path("knot.xyz")).code,
            0);
  const CliRun knot = Dotctl(flag_ + "triangulate " + Path("knot.xyz"));
  EXPECT_EQ(knot.code, 4) << knot.out;
  EXPECT_NE(knot.out.find("not Delaunay-triangulable"), std::string::npos);
  EXPECT_EQ(Dotctl(flag_ + "triangulate --no-such-flag x").code, 2);
  EXPECT_EQ(Dotctl(flag_ + "triangulate /nonexistent.xyz").code, 2);
  const CliRun down = Dotctl("--server 127.0.0.1:1 --timeout 2 triangulate " +
                             Path("knot.xyz"));
  EXPECT_EQ(down.code, 3) << down.out;
  EXPECT_EQ(Dotctl("--server 127.0.0.1:1 health").code, 3);
  const CliRun health = Dotctl(flag_ + "health");
  EXPECT_EQ(health.code, 0);
  EXPECT_NE(health.out.find("SERVING"), std::string::npos);
  std::ofstream(Path("bad.xyz")) << "0 0 0\n1 0 0\n1 0 0\n";
  const CliRun bad = Dotctl(flag_ + "triangulate " + Path("bad.xyz"));
  EXPECT_EQ(bad.code, 1) << bad.out;
  EXPECT_NE(
      bad.out.find(
          "INVALID_ARGUMENT: vertices 1 and 2 are consecutive duplicates"),
      std::string::npos)
      << bad.out;
}

TEST_F(CliTest, GlobalOptionsWorkAfterTheSubcommand) {
  // flag_ is "--server ADDRESS "; here it follows the subcommand.
  const CliRun health = Dotctl("health " + flag_);
  EXPECT_EQ(health.code, 0) << health.out;
  EXPECT_NE(health.out.find("SERVING"), std::string::npos) << health.out;
}

TEST_F(CliTest, BothBinariesPrintTheirVersion) {
  const CliRun dotctl = Dotctl("--version");
  EXPECT_EQ(dotctl.code, 0);
  EXPECT_EQ(dotctl.out.rfind("dotctl ", 0), 0u) << dotctl.out;
  const std::string command = std::string(DOT_SERVER_PATH) + " --version 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char line[256] = {};
  const bool read = std::fgets(line, sizeof line, pipe) != nullptr;
  EXPECT_EQ(::pclose(pipe), 0);
  ASSERT_TRUE(read);
  EXPECT_EQ(std::string(line).rfind("dot-server ", 0), 0u) << line;
}

TEST_F(CliTest, BatchLoadInfoAndHelp) {
  fs::create_directories(dir_ / "in");
  for (int i = 0; i < 5; ++i) {
    ASSERT_EQ(Dotctl("generate curve spiral -n " + std::to_string(50 + 20 * i) +
                     " -o " + Path("in/s" + std::to_string(i) + ".xyz"))
                  .code,
              0);
  }
  const CliRun batch =
      Dotctl(flag_ + "batch " + Path("in") + " -o " + Path("out"));
  EXPECT_EQ(batch.code, 0) << batch.out;
  EXPECT_NE(batch.out.find("5 of 5 polygons answered"), std::string::npos)
      << batch.out;
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(fs::exists(dir_ / "out" / ("s" + std::to_string(i) + ".obj")));
  }
  const CliRun load = Dotctl(flag_ + "load -c 3 -r 30 -n 80 --json");
  EXPECT_EQ(load.code, 0) << load.out;
  EXPECT_NE(load.out.find("\"requests\":30,\"succeeded\":30,\"errors\":0"),
            std::string::npos)
      << load.out;
  // Over two TriangulateBatch streams, five requests in flight.
  const CliRun streamed =
      Dotctl(flag_ + "load --batch --channels 2 -c 5 -r 40 -n 80 --json");
  EXPECT_EQ(streamed.code, 0) << streamed.out;
  EXPECT_NE(streamed.out.find("\"requests\":40,\"succeeded\":40,\"errors\":0"),
            std::string::npos)
      << streamed.out;
  const CliRun info = Dotctl(flag_ + "info");
  EXPECT_EQ(info.code, 0);
  EXPECT_NE(info.out.find("AGPL-3.0-or-later"), std::string::npos);
  const CliRun help = Dotctl("load --help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("--concurrency"), std::string::npos);
}

}  // namespace
}  // namespace dot
