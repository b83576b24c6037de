// goal-rush-server, the game's own program, run as a user runs it: physics-server's
// command line (--help, its flags, its exit codes, its "listening on" line on stdout
// and its log on stderr) with goal rush's rules built in.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "physics_testing/testing.h"

namespace {

using namespace std::chrono_literals;

struct Finished {
  int exit_code = -1;
  std::string output;  // the stream the command line chose
};

// Runs `command` through the shell to its end: its exit code and what it wrote to
// the stream the command redirects to stdout.
Finished run_to_end(const std::string& command) {
  Finished finished;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return finished;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) {
    finished.output.append(buffer, n);
  }
  const int status = pclose(pipe);
  finished.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return finished;
}

TEST(GoalRushServer, HelpNamesPhysicsServersFlagsAndExits0) {
  const Finished help = run_to_end(GOAL_RUSH_SERVER_EXE " --help 2>/dev/null");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* text : {"Usage: goal-rush-server", "--token", "--token-file",
                           "--lockstep-players", "--port", "--scene", "goal-rush.textproto"}) {
    EXPECT_NE(help.output.find(text), std::string::npos) << text << " in\n" << help.output;
  }
  // Its rules are built in: no --rules.
  EXPECT_EQ(help.output.find("--rules"), std::string::npos) << help.output;
}

TEST(GoalRushServer, ABadArgumentExits2AndSaysWhatWasWrong) {
  const Finished bad = run_to_end(GOAL_RUSH_SERVER_EXE " 7777 2>&1 >/dev/null");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("7777"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("--help"), std::string::npos) << bad.output;
  const Finished port = run_to_end(GOAL_RUSH_SERVER_EXE " --port 99999 2>&1 >/dev/null");
  EXPECT_EQ(port.exit_code, 2);
  EXPECT_NE(port.output.find("not in range 0 to 65535"), std::string::npos) << port.output;
}

// The "listening on" line that physics_testing::ServerProcess reads, the token a
// client must send, and the log on stderr (ServerProcess::log).
TEST(GoalRushServer, ListensAsPhysicsServerDoesAndAsksForItsToken) {
  physics_testing::ProcessOptions options;
  options.executable = GOAL_RUSH_SERVER_EXE;
  options.extra_args = {"--token", "s3cret"};
  physics_testing::ServerProcess server(options);

  client::ClientConfig stranger_config = server.client_config("stranger");
  stranger_config.token = "wrong";
  client::Client stranger(stranger_config);
  EXPECT_FALSE(stranger.connect(5s));
  ASSERT_TRUE(stranger.last_error().server) << stranger.last_error().to_string();
  EXPECT_EQ(stranger.last_error().server->code, client::ErrorCode::BadToken);

  client::Client player(server.client_config("player"));
  ASSERT_TRUE(player.connect(5s)) << player.last_error().to_string() << "\n" << server.log();
  const auto named = [&](const client::BodyShape& shape) {
    return shape.body_id == player.welcome().body_id && shape.name == "left player";
  };
  // Goal rush's rules made its body: the left player.
  const auto& bodies = player.welcome().bodies;
  EXPECT_TRUE(std::any_of(bodies.begin(), bodies.end(), named));
  player.disconnect();

  EXPECT_EQ(server.stop(), 0) << server.log();
  const std::string log = server.log();
  EXPECT_NE(log.find("[goal-rush-server] [info] serving at 60 ticks/s"), std::string::npos) << log;
  EXPECT_NE(log.find("token required, with game rules"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped after"), std::string::npos) << log;
}

}  // namespace
