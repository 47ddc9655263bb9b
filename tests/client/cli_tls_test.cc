// SPDX-License-Identifier: AGPL-3.0-or-later
// TLS and mutual TLS on loopback, and dotctl's subcommands end to end
// against a real server.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fixtures/dotctl_run.h"
#include "fixtures/service_fixture.h"
#include "remote/grpc_calls.h"

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

TEST(TlsTest, BadTlsFilesAreNamedNotBlamedOnTheAddress) {
  // Before: junk certificates, keys or CAs, and a directory, all ended in
  // "cannot listen on 127.0.0.1:0".
  const fs::path d = MakeCertificates();
  { std::ofstream(d / "junk.pem") << "not a certificate\n"; }
  struct Case {
    std::string cert, key, ca, words;
  };
  const std::string cert = (d / "server.pem").string(),
                    key = (d / "server.key").string(),
                    junk = (d / "junk.pem").string();
  const Case cases[] = {
      {junk, key, "", "--tls-cert: '" + junk + "' holds no PEM CERTIFICATE"},
      {cert, junk, "", "--tls-key: '" + junk + "' holds no PEM PRIVATE KEY"},
      {cert, key, junk,
       "--tls-client-ca: '" + junk + "' holds no PEM CERTIFICATE"},
      {d.string(), key, "", "--tls-cert: cannot read '" + d.string() + "'"},
      {cert, cert, "", "--tls-key: '" + cert + "' holds no PEM PRIVATE KEY"},
      // A key that is not the certificate's: only gRPC can tell.
      {cert, (d / "client.key").string(), "", "gRPC refused the TLS"},
  };
  for (const Case& c : cases) {
    auto config = testing::LoopbackConfig();
    config.tls.cert = c.cert;
    config.tls.key = c.key;
    config.tls.client_ca = c.ca;
    std::string error;
    EXPECT_EQ(server::DotServer::Start(config, &error), nullptr) << c.words;
    EXPECT_NE(error.find(c.words), std::string::npos)
        << "expected '" << c.words << "' in: " << error;
  }
  fs::remove_all(d);
}

TEST(TlsTest, ContainerHealthCheckPassesWithTlsOn) {
  // Before: the image's HEALTHCHECK (`dotctl health`) read the server's
  // DOT_TLS_CERT/DOT_TLS_KEY as a client certificate, spoke plaintext to
  // the TLS port and exited 3: every TLS container was unhealthy.
  const fs::path d = MakeCertificates();
  auto config = testing::LoopbackConfig();
  config.tls.cert = (d / "server.pem").string();
  config.tls.key = (d / "server.key").string();
  config.tls.client_ca = (d / "ca.pem").string();  // mutual TLS, even
  config.health_listen = "127.0.0.1:0";
  auto s = testing::StartServer(config);
  ASSERT_GT(s.server->health_port(), 0);
  const std::string health =
      "127.0.0.1:" + std::to_string(s.server->health_port());
  // The Dockerfile's HEALTHCHECK, with the server's environment.
  const std::string env = "DOT_TLS_CERT='" + config.tls.cert +
                          "' DOT_TLS_KEY='" + config.tls.key + "' ";
  CliRun r = testing::RunShell(env +
                               "env -u DOT_TLS_CA -u DOT_TLS_CERT -u "
                               "DOT_TLS_KEY " DOT_DOTCTL_PATH " --server " +
                               health + " health");
  EXPECT_EQ(r.code, 0) << r.out;
  // Only health is served there: the API stays behind TLS.
  client::ConnectionFlags plain;
  plain.server = health;
  EXPECT_EQ(CallOver(plain).error_code(), grpc::StatusCode::UNIMPLEMENTED);
  // A drain turns it NOT_SERVING like the main port.
  s.server->Drain(std::chrono::milliseconds(0));
  r = testing::RunShell(std::string(DOT_DOTCTL_PATH) + " --server " + health +
                        " --timeout 2 health");
  EXPECT_NE(r.code, 0) << r.out;
  fs::remove_all(d);
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// dot-server run to its exit (bounded: `timeout` ends one that starts),
// with `env` before it on the shell line; stdout and stderr together.
CliRun RunServerWith(const std::string& env, const std::string& args = "") {
  const std::string cmd = "DOT_METRICS_PORT=0 " + env + " timeout 5 " +
                          DOT_SERVER_PATH + " --listen 127.0.0.1:0 " + args +
                          " 2>&1";
  CliRun r{0, ""};
  FILE* p = ::popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A wavy loop around the z axis, counter-clockwise seen from +z, with
// every normal (0, 0, nz).
void WriteWavyLoop(const std::string& path, int nz) {
  std::ofstream out(path);
  out.precision(17);
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    out << std::cos(t) << ' ' << std::sin(t) << ' ' << 0.3 * std::cos(3 * t)
        << " 0 0 " << nz << '\n';
  }
}

class CliTest : public ::testing::Test {
 protected:
  // dotctl with stdout and stderr apart (the shared runner joins them):
  // `args` may redirect stdin and stdout, not stderr.
  struct Split {
    int code;
    std::string out, err;
  };
  Split Run(const std::string& args) {
    const std::string err = Path("stderr.txt");
    const CliRun r = Dotctl(args + " 2> " + err + "; exit $?");
    Split s{r.code, r.out, Slurp(err)};
    fs::remove(err);
    return s;
  }
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

TEST_F(CliTest, DashIsStdinAndStdout) {
  ASSERT_EQ(Dotctl("generate curve mobius -n 60 -o " + Path("m.xyz")).code, 0);
  // A polygon from stdin: its mesh goes to stdout (there is no "beside"),
  // the summary to stderr.
  Split split = Run(flag_ + "triangulate - < " + Path("m.xyz"));
  EXPECT_EQ(split.code, 0) << split.err;
  EXPECT_EQ(split.out.rfind("v ", 0), 0u) << split.out;
  EXPECT_TRUE(Has(split.err, "stdin: ok: 58 triangles")) << split.err;
  CliRun r;
  // OBJ from stdin.
  {
    std::ofstream obj(Path("m.obj"));
    obj.precision(17);
    for (const Vec3& v : MakeCurve(Curve::kMobius, 60)) {
      obj << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    }
  }
  r = Dotctl(flag_ + "triangulate - --input-format obj -o " + Path("b.ply") +
             " < " + Path("m.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(Slurp(Path("b.ply")).rfind("ply\n", 0), 0u);
  // -o -: the mesh on stdout in --format, the summary on stderr.
  split = Run(flag_ + "triangulate " + Path("m.xyz") + " -o - --format off");
  EXPECT_EQ(split.code, 0) << split.err;
  EXPECT_EQ(split.out.rfind("OFF\n", 0), 0u) << split.out;
  EXPECT_TRUE(Has(split.err, "ok: 58 triangles")) << split.err;
  // --format decides when -o has no extension.
  r = Dotctl(flag_ + "triangulate " + Path("m.xyz") + " -o " + Path("noext") +
             " --format ply");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(Slurp(Path("noext")).rfind("ply\n", 0), 0u);
  // /dev/stdin is a stream too: nothing is written into /dev.
  r = Dotctl(flag_ + "triangulate /dev/stdin < " + Path("m.xyz") + " > " +
             Path("d.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(fs::exists("/dev/stdin.tri.obj"));
  fs::remove("/dev/stdin.tri.obj");
  EXPECT_EQ(Slurp(Path("d.obj")).rfind("v ", 0), 0u);
  // batch: one polygon from stdin, its mesh in -o DIR.
  r = Dotctl(flag_ + "batch - " + Path("m.xyz") + " -o " + Path("out") + " < " +
             Path("m.obj") + " --input-format obj");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out, "2 of 2 polygons answered")) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "stdin.obj"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "m.obj"));
  // generate writes to stdout too.
  r = Dotctl("generate curve spiral -n 30 -o - > " + Path("s.xyz"));
  EXPECT_EQ(r.code, 0) << r.out;
  PolygonData spiral;
  EXPECT_TRUE(ReadPolygonFile(Path("s.xyz"), &spiral).ok());
  EXPECT_EQ(spiral.vertices.size(), 30u);
}

// batch keys its stream's answers by input: a file named twice (or named
// and found in a directory named) is sent once, with a note.
TEST_F(CliTest, BatchSendsAFileNamedTwiceOnce) {
  ASSERT_EQ(Dotctl("generate curve monkey -n 60 -o " + Path("k.xyz")).code, 0);
  const CliRun r =
      Dotctl(flag_ + "batch --json " + Path("k.xyz") + " " + dir_.string() +
             "/./k.xyz " + dir_.string() + " -o " + Path("out"));
  EXPECT_EQ(r.code, 0) << r.out;
  size_t reports = 0;
  for (size_t at = 0;
       (at = r.out.find("\"outcome\":\"ok\"", at)) != std::string::npos; ++at) {
    ++reports;
  }
  EXPECT_EQ(reports, 1u) << r.out;
  EXPECT_TRUE(Has(r.out, "is named more than once: sent once")) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "k.obj")) << r.out;
}

TEST_F(CliTest, OutputCheckedBeforeTheWorkAndJsonForEveryOutcome) {
  ASSERT_EQ(Dotctl("generate curve mobius -n 60 -o " + Path("m.xyz")).code, 0);
  const std::string m = Path("m.xyz");
  // A missing directory: refused before the call, with the reason, and a
  // JSON object that says no call was made.
  const std::string missing = Path("no/such/dir/m.obj");
  const Split split = Run(flag_ + "triangulate " + m + " --json -o " + missing);
  EXPECT_EQ(split.code, 2) << split.out;
  EXPECT_TRUE(Has(split.out, "\"version\":1")) << split.out;
  EXPECT_TRUE(Has(split.out, "\"outcome\":\"output_error\"")) << split.out;
  EXPECT_TRUE(Has(split.out, "\"rpc_status\":null,")) << split.out;
  EXPECT_TRUE(Has(split.out, "\"summary\":null}")) << split.out;
  EXPECT_TRUE(Has(split.err,
                  "cannot write '" + missing + "': No such file or directory"))
      << split.err;
  CliRun r;
  // A bad extension, or one --format contradicts: no work, no "ok".
  r = Dotctl(flag_ + "triangulate " + m + " -o " + Path("x.stla"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(Has(r.out, "cannot tell the mesh format")) << r.out;
  EXPECT_FALSE(Has(r.out, "ok:")) << r.out;
  r = Dotctl(flag_ + "triangulate " + m + " -o " + Path("x.obj") +
             " --format ply");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_FALSE(Has(r.out, "ok:")) << r.out;
  EXPECT_FALSE(fs::exists(Path("x.obj")));
  // An output that is a directory takes the mesh inside it.
  fs::create_directories(dir_ / "meshes");
  r = Dotctl(flag_ + "triangulate " + m + " -o " + Path("meshes"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "meshes" / "m.obj"));
  // Several inputs and -o naming a mesh file.
  ASSERT_EQ(Dotctl("generate curve monkey -n 60 -o " + Path("k.xyz")).code, 0);
  r = Dotctl(flag_ + "triangulate " + m + " " + Path("k.xyz") + " -o " +
             Path("y.obj"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(Has(r.out, "need a directory")) << r.out;
  // An unreadable input gets its JSON object too.
  r = Dotctl(flag_ + "triangulate " + Path("none.xyz") + " --json 2>/dev/null");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(Has(r.out, "\"outcome\":\"input_error\"")) << r.out;
  EXPECT_TRUE(Has(r.out, "No such file or directory")) << r.out;
  // A write that fails after the work says so: not OK without an error.
  r = Dotctl(flag_ + "triangulate " + m +
             " --json --format obj -o /dev/full 2>/dev/null");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_TRUE(Has(r.out, "\"outcome\":\"write_failed\"")) << r.out;
  EXPECT_TRUE(Has(r.out, "No space left on device")) << r.out;
  EXPECT_FALSE(Has(r.out, "\"error\":\"\"")) << r.out;
  // Success: the outcome, the exit code and where the mesh went.
  r = Dotctl(flag_ + "triangulate " + m + " --json -o " + Path("ok.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out,
                  "\"outcome\":\"ok\",\"exit_code\":0,"
                  "\"rpc_status\":\"OK\",\"error\":\"\",\"output\":\"" +
                      Path("ok.obj") + "\""))
      << r.out;
}

TEST_F(CliTest, ErrorsOnStderrQuietAndVerbose) {
  ASSERT_EQ(Dotctl("generate curve mobius -n 60 -o " + Path("m.xyz")).code, 0);
  std::ofstream(Path("bad.xyz")) << "0 0 0\n1 0 0\n1 0 0\n0 1 1\n";
  // A server-side failure: on stderr only.
  Split split = Run(flag_ + "triangulate " + Path("bad.xyz"));
  EXPECT_EQ(split.code, 1);
  EXPECT_EQ(split.out, "");
  EXPECT_TRUE(Has(split.err, "INVALID_ARGUMENT: vertices 1 and 2"))
      << split.err;
  split = Run("--server 127.0.0.1:1 health");
  EXPECT_EQ(split.code, 3);
  EXPECT_EQ(split.out, "");
  EXPECT_TRUE(Has(split.err, "UNREACHABLE")) << split.err;
  CliRun r;
  // -q: nothing but errors, before or after the subcommand.
  r = Dotctl(flag_ + "-q triangulate " + Path("m.xyz") + " -o " +
             Path("q.obj"));
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(fs::exists(Path("q.obj")));
  r = Dotctl(flag_ + "health --quiet");
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, "");
  r = Dotctl(flag_ + "-q triangulate " + Path("bad.xyz"));
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(Has(r.out, "INVALID_ARGUMENT")) << r.out;
  // -v: a timing line per request, on stderr.
  split = Run(flag_ + "triangulate " + Path("m.xyz") + " -o " + Path("v.obj") +
              " -v");
  EXPECT_EQ(split.code, 0);
  EXPECT_TRUE(Has(split.err, "m.xyz: OK in ")) << split.err;
  EXPECT_TRUE(Has(split.err, " ms (compute ")) << split.err;
  EXPECT_FALSE(Has(split.out, "OK in")) << split.out;
  split = Run(flag_ + "-v load -c 1 -r 2 -n 40");
  EXPECT_EQ(split.code, 0);
  EXPECT_TRUE(Has(split.err, "request 1: OK in ")) << split.err;
  EXPECT_EQ(Dotctl(flag_ + "-q -v health").code, 2);
}

TEST_F(CliTest, MistypedSubcommandGetsASuggestion) {
  CliRun r = Dotctl("triangulat x.xyz");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.out,
                  "dotctl: unknown command 'triangulat'; did you mean "
                  "'triangulate'?"))
      << r.out;
  r = Dotctl("generate curv monkey -o x.xyz");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.out, "did you mean 'curve'?")) << r.out;
}

TEST_F(CliTest, ExitCodesOfEverySubcommand) {
  ASSERT_EQ(Dotctl("generate curve mobius -n 60 -o " + Path("m.xyz")).code, 0);
  ASSERT_EQ(Dotctl("generate curve trefoil -n 90 -o " + Path("knot.xyz")).code,
            0);
  const std::string down = "--server 127.0.0.1:1 --timeout 2 ";
  const std::string m = Path("m.xyz");
  EXPECT_EQ(Dotctl(down + "load -r 3 -n 40").code, 3);
  EXPECT_EQ(Dotctl(down + "load --batch -r 3 -n 40").code, 3);
  EXPECT_EQ(Dotctl(down + "info").code, 3);
  EXPECT_EQ(Dotctl(down + "source -o " + Path("src.tgz")).code, 3);
  EXPECT_FALSE(fs::exists(Path("src.tgz")));
  EXPECT_EQ(Dotctl(down + "batch " + m).code, 3);
  EXPECT_EQ(Dotctl(down + "triangulate " + m).code, 3);
  EXPECT_EQ(Dotctl(down + "health").code, 3);
  EXPECT_EQ(Dotctl(flag_ + "load -r 2 -n 40").code, 0);
  EXPECT_EQ(Dotctl(flag_ + "load -r 2 --files " + Path("knot.xyz")).code, 4);
  EXPECT_EQ(
      Dotctl(flag_ + "batch " + Path("knot.xyz") + " -o " + Path("o")).code, 4);
  EXPECT_EQ(Dotctl(flag_ + "batch " + Path("none.xyz")).code, 2);
  EXPECT_EQ(Dotctl(flag_ + "load --files " + Path("none.xyz")).code, 2);
  EXPECT_EQ(
      Dotctl("generate hole " + Path("none.off") + " -o " + Path("h.xyz")).code,
      2);
  EXPECT_EQ(Dotctl(flag_ + "info").code, 0);
}

TEST_F(CliTest, ServerNamesTheEnvironmentVariableOfABadValue) {
  CliRun r = RunServerWith("DOT_THREADS=abc");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(Has(r.out, "DOT_THREADS='abc' is not an integer")) << r.out;
  r = RunServerWith("DOT_THREADS=-3");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(Has(r.out,
                  "DOT_THREADS='-3' is out of range: it must be at "
                  "least 0"))
      << r.out;
  for (const char* env :
       {"DOT_QUEUE_SIZE=-1", "DOT_MAX_CONNECTION_AGE_S=-5",
        "DOT_DRAIN_SECONDS=-1", "DOT_CACHE_MB=-3", "DOT_METRICS_PORT=70000",
        "DOT_DELAUNAY_HELPERS=-2", "DOT_FILL_MAX_FACES=-1"}) {
    r = RunServerWith(env);
    EXPECT_EQ(r.code, 2) << env << ": " << r.out;
    const std::string name =
        std::string(env).substr(0, std::string(env).find('='));
    EXPECT_TRUE(Has(r.out, name + "='")) << env << ": " << r.out;
  }
  // From the command line the flag is named (the environment is not).
  r = RunServerWith("", "--threads x3");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(Has(r.out, "--threads: 'x3' is not an integer")) << r.out;
}

TEST_F(CliTest, LoadVariesItsPolygonsUnlessAskedNot) {
  CliRun r = Dotctl(flag_ + "load -c 1 -r 6 -n 60 --json");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out, "\"succeeded\":6,")) << r.out;
  EXPECT_TRUE(Has(r.out, "\"polygons\":\"rotated\"")) << r.out;
  EXPECT_TRUE(Has(r.out, "\"cache_hits\":0,")) << r.out;
  r = Dotctl(flag_ + "load --batch -c 2 -r 6 -n 60 --json");
  EXPECT_TRUE(Has(r.out, "\"cache_hits\":0,")) << r.out;
  r = Dotctl(flag_ + "load -c 1 -r 6 -n 60 --same-polygon --json");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out, "\"polygons\":\"same\"")) << r.out;
  EXPECT_TRUE(Has(r.out, "\"cache_hits\":5,")) << r.out;
  r = Dotctl(flag_ + "load -c 1 -r 3 -n 60");
  EXPECT_TRUE(Has(r.out, "each request a randomly rotated copy")) << r.out;
}

TEST_F(CliTest, SourceIsWrittenAtomically) {
  // The fixture's server has no archive: the call fails and leaves nothing.
  CliRun r = Dotctl(flag_ + "source -o " + Path("src.tgz"));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_FALSE(fs::exists(Path("src.tgz")));
  for (const auto& e : fs::directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().find(".src.tgz"), std::string::npos)
        << e.path();
  }
  // One that has one: to a file, and to stdout.
  const std::string bytes(300000, 'x');
  std::ofstream(Path("archive.tar.gz"), std::ios::binary) << bytes;
  auto config = testing::LoopbackConfig();
  config.service.source_archive = Path("archive.tar.gz");
  auto s = testing::StartServer(config);
  const std::string other = "--server " + s.address + " ";
  r = Dotctl(other + "source -o " + Path("src.tgz"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Slurp(Path("src.tgz")) == bytes);
  const Split piped = Run(other + "source -o -");
  EXPECT_EQ(piped.code, 0) << piped.err;
  EXPECT_TRUE(piped.out == bytes) << piped.out.size() << " bytes";
  EXPECT_FALSE(fs::exists(fs::current_path() / "-"));
}

TEST_F(CliTest, LoopsAsExportersWriteThem) {
  const std::vector<Vec3> loop = MakeCurve(Curve::kMobius, 60);
  // An xyz loop that repeats its first point at the end.
  {
    std::ofstream xyz(Path("closed.xyz"));
    xyz.precision(17);
    for (size_t i = 0; i <= loop.size(); ++i) {
      const Vec3& v = loop[i % loop.size()];
      xyz << v.x << ' ' << v.y << ' ' << v.z << '\n';
    }
  }
  CliRun r = Dotctl(flag_ + "triangulate " + Path("closed.xyz") + " -o " +
                    Path("closed.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out, "ok: 58 triangles")) << r.out;
  EXPECT_TRUE(Has(r.out, "note: dropped the last vertex")) << r.out;
  r = Dotctl(flag_ + "triangulate " + Path("closed.xyz") + " --json -o " +
             Path("closed.obj") + " 2>/dev/null");
  EXPECT_TRUE(Has(r.out, "\"notes\":[\"dropped the last vertex")) << r.out;
  // OBJ with one "l a b" line per edge, as Blender writes it.
  {
    std::ofstream obj(Path("edges.obj"));
    obj.precision(17);
    obj << "# Blender\no Loop\n";
    for (const Vec3& v : loop) {
      obj << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    }
    for (size_t i = 0; i < loop.size(); ++i) {
      const size_t a = (i * 7) % loop.size();  // edges in a shuffled order
      obj << "l " << (a % 2 ? a + 1 : (a + 1) % loop.size() + 1) << ' '
          << (a % 2 ? (a + 1) % loop.size() + 1 : a + 1) << '\n';
    }
  }
  r = Dotctl(flag_ + "triangulate " + Path("edges.obj") + " -o " +
             Path("edges.tri.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out, "ok: 58 triangles")) << r.out;
  std::ofstream(Path("open.obj")) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\n"
                                     "l 1 2\nl 2 3\nl 3 4\n";
  r = Dotctl(flag_ + "triangulate " + Path("open.obj"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(Has(r.out, "do not close into a loop")) << r.out;
  // A loop running against its normals: accepted, with a warning.
  WriteWavyLoop(Path("up.xyz"), 1);
  WriteWavyLoop(Path("down.xyz"), -1);
  r = Dotctl(flag_ + "triangulate " + Path("up.xyz") + " --json -o " +
             Path("up.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out,
                  "\"faces_against_normals\":0,"
                  "\"orientation_contradicts_normals\":false"))
      << r.out;
  r = Dotctl(flag_ + "triangulate " + Path("down.xyz") + " -o " +
             Path("down.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(Has(r.out,
                  "WARNING: 38 of 38 triangles face against the given "
                  "normals"))
      << r.out;
  r = Dotctl(flag_ + "triangulate " + Path("down.xyz") + " --json -o " +
             Path("down.obj"));
  EXPECT_TRUE(Has(r.out, "\"orientation_contradicts_normals\":true")) << r.out;
}

}  // namespace
}  // namespace dot
