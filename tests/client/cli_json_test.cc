// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl for scripts: --json on every subcommand that had none (generate,
// health, info, source), each printing the versioned envelope (README,
// "Using the client") with its own fields, for success and failure alike;
// and shell completion.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "fixtures/dotctl_run.h"
#include "fixtures/service_fixture.h"

namespace dot {
namespace {

using testing::Dotctl;

// The one line of `out` that is the envelope (notes may precede it).
std::string Envelope(const std::string& out) {
  const size_t at = out.find("{\"version\":1,");
  if (at == std::string::npos) return "";
  return out.substr(at, out.find('\n', at) - at);
}

void ExpectField(const std::string& json, const std::string& field) {
  EXPECT_NE(json.find(field), std::string::npos) << json;
}

class JsonCliTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::TempDir("json-cli"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const {
    return (dir_ / name).string();
  }
  std::filesystem::path dir_;
};

TEST_F(JsonCliTest, GenerateSaysWhatItMade) {
  auto r =
      Dotctl("generate curve monkey -n 30 -o " + Path("m.xyz") + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  std::string e = Envelope(r.out);
  ExpectField(e, "\"outcome\":\"ok\"");
  ExpectField(e, "\"output\":\"" + Path("m.xyz") + "\"");
  ExpectField(e, "\"vertices\":30");
  r = Dotctl("generate loops tube -n 20 -o - --json");  // JSON on stderr
  ExpectField(Envelope(r.out), "\"vertices\":40");
  r = Dotctl("generate network cube -s 2 -o " + Path("c.obj") + " --json");
  ExpectField(Envelope(r.out), "\"polylines\":12");
  r = Dotctl("generate holes " + std::string(DOT_MESH_DIR) +
             "/elephant.off -k 2 -t 30 -o " + Path("e.off") + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  e = Envelope(r.out);
  ExpectField(e, "\"holes\":2");
  ExpectField(e, "\"removed\":\"" + Path("e.removed.off") + "\"");
  // Failures too: an unknown curve is unusable input (exit 2), an
  // unreadable mesh as well.
  r = Dotctl("generate curve nonesuch -o " + Path("x.xyz") + " --json");
  EXPECT_EQ(r.code, 2);
  ExpectField(Envelope(r.out), "\"outcome\":\"input_error\"");
  r = Dotctl("generate hole " + Path("missing.off") + " -o " + Path("h.xyz") +
             " --json");
  EXPECT_EQ(r.code, 2);
  ExpectField(Envelope(r.out), "\"exit_code\":2");
}

TEST_F(JsonCliTest, HealthInfoAndSourceAnswerInJson) {
  const testing::RunningServer server =
      testing::StartServer(testing::LoopbackConfig());
  const std::string flag = "--server " + server.address + " ";
  auto r = Dotctl(flag + "health --json");
  ASSERT_EQ(r.code, 0) << r.out;
  std::string e = Envelope(r.out);
  ExpectField(e, "\"rpc_status\":\"OK\"");
  ExpectField(e, "\"status\":\"SERVING\"");
  // A service the server does not know: NOT_FOUND, as the health
  // protocol says; the server is reachable.
  r = Dotctl(flag + "health --service nonesuch --json");
  EXPECT_EQ(r.code, 1) << r.out;
  e = Envelope(r.out);
  ExpectField(e, "\"rpc_status\":\"NOT_FOUND\"");
  ExpectField(e, "\"status\":\"SERVICE_UNKNOWN\"");
  r = Dotctl(flag + "info --json");
  ASSERT_EQ(r.code, 0) << r.out;
  e = Envelope(r.out);
  ExpectField(e, "\"server_info\":{\"version\":");
  ExpectField(e, "\"limits\":{");
  // The loopback fixture has no source archive: the call fails, the
  // envelope says so.
  r = Dotctl(flag + "source -o " + Path("s.tgz") + " --json");
  EXPECT_NE(r.code, 0);
  e = Envelope(r.out);
  ExpectField(e, "\"outcome\":\"call_failed\"");
  ExpectField(e, "\"bytes\":0");
  EXPECT_FALSE(std::filesystem::exists(Path("s.tgz")));
  r = Dotctl(flag + "source -o /nonexistent/dir/s.tgz --json");
  EXPECT_EQ(r.code, 2);
  ExpectField(Envelope(r.out), "\"outcome\":\"output_error\"");
}

TEST_F(JsonCliTest, HealthOfNoServerIsUnreachable) {
  const auto r =
      Dotctl("--server unix:" + Path("nobody.sock") + " health --json");
  EXPECT_EQ(r.code, 3);
  const std::string e = Envelope(r.out);
  ExpectField(e, "\"rpc_status\":\"UNAVAILABLE\"");
  ExpectField(e, "\"status\":\"UNREACHABLE\"");
}

// Connection flags that make no channel (an unreadable CA file): every
// subcommand that calls the server says so in its envelope, on stdout.
TEST_F(JsonCliTest, AnUnusableConnectionIsAnEnvelopeToo) {
  const std::string tls = "--tls-ca " + Path("missing-ca.pem") + " ";
  for (const std::string& cmd :
       {std::string("health --json"), std::string("info --json"),
        "triangulate " + std::string(DOT_TEST_DATA_DIR) +
            "/tetgen_aborts.xyz -o " + Path("t.obj") + " --json"}) {
    const auto r = Dotctl(tls + cmd);
    EXPECT_EQ(r.code, 2) << cmd << ": " << r.out;
    const std::string e = Envelope(r.out);
    ExpectField(e, "\"outcome\":\"connection_error\"");
    ExpectField(e, "missing-ca.pem");
  }
}

// bash completion from the CLI's own definition: subcommands at each
// level, then that subcommand's options (and the global ones after it).
TEST(CompletionCliTest, OffersSubcommandsAndTheirOptions) {
  auto complete = [](const std::string& words, int cword) {
    const std::string script = "source <(" + std::string(DOT_DOTCTL_PATH) +
                               " completion bash); COMP_WORDS=(" + words +
                               "); COMP_CWORD=" + std::to_string(cword) +
                               "; _dotctl; echo \"[${COMPREPLY[*]}]\"";
    return testing::RunShell("bash -c '" + script + "'").out;
  };
  EXPECT_NE(complete("dotctl gen", 1).find("[generate"), std::string::npos);
  const std::string net = complete("dotctl generate network --k", 3);
  EXPECT_NE(net.find("--keep-every"), std::string::npos) << net;
  const std::string sub = complete("dotctl generate ne", 2);
  EXPECT_NE(sub.find("network"), std::string::npos) << sub;
  const std::string after = complete("dotctl surface x.obj --ti", 3);
  EXPECT_NE(after.find("--timeout"), std::string::npos) << after;
  EXPECT_NE(after.find("--time-budget-ms"), std::string::npos) << after;
  // zsh gets the same function through bashcompinit.
  const auto zsh = Dotctl("completion zsh");
  EXPECT_EQ(zsh.code, 0);
  EXPECT_NE(zsh.out.find("bashcompinit"), std::string::npos);
  EXPECT_NE(Dotctl("completion fish").code, 0);
}

}  // namespace
}  // namespace dot
