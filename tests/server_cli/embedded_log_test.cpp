// Where an embedded server::Server writes its log: through spdlog's default logger,
// the process's (stdout, spdlog's default), until the program sends it to stderr with
// server::use_stderr_log, as physics-server and every program made with
// server::run_server_cli do before serving (docs/SERVER.md, "Running it").
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "physics_testing/testing.h"
#include "server/log_format.h"

namespace {

using namespace std::chrono_literals;

// A player joins and leaves an embedded server that logs every join; what was written
// to stdout and to stderr meanwhile.
struct Written {
  std::string out;
  std::string err;
};

Written run_embedded_server(const std::string& player_name) {
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  {
    server::ServerConfig config = physics_testing::test_server_config();
    config.log_level = server::LogLevel::Info;
    physics_testing::InProcessServer server(scene::default_scene(), config);
    client::Client player(server.client_config(player_name));
    EXPECT_TRUE(player.connect(5s)) << player.last_error().to_string();
    player.disconnect();
  }
  Written written;
  written.out = testing::internal::GetCapturedStdout();
  written.err = testing::internal::GetCapturedStderr();
  return written;
}

TEST(EmbeddedServerLog, GoesToStdoutUntilTheProgramSendsItToStderr) {
  const Written before = run_embedded_server("probe-before");
  EXPECT_NE(before.out.find("'probe-before'"), std::string::npos) << before.out;
  EXPECT_EQ(before.err.find("probe-before"), std::string::npos) << before.err;

  server::use_stderr_log("embedded-game", server::LogFormat::Text);
  const Written after = run_embedded_server("probe-after");
  EXPECT_EQ(after.out.find("probe-after"), std::string::npos) << after.out;
  EXPECT_NE(after.err.find("[embedded-game] [info] client 1 'probe-after'"), std::string::npos)
      << after.err;
}

}  // namespace
