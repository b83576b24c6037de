// physics-client, the executable, against a real server: it prints one line per
// snapshot (JSON with --json) and exits non-zero with the server's error when it
// is refused.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>

#include "harness.h"

namespace itest {
namespace {

struct CommandRun {
  int exit_code = -1;
  std::vector<std::string> lines;
};

// Runs a command (stderr merged into stdout) and collects its lines.
CommandRun run_command(const std::string& command) {
  CommandRun run;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return run;
  std::string line;
  for (int c = std::fgetc(pipe); c != EOF; c = std::fgetc(pipe)) {
    if (c == '\n') {
      run.lines.push_back(line);
      line.clear();
    } else {
      line.push_back(static_cast<char>(c));
    }
  }
  if (!line.empty()) run.lines.push_back(line);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::string client_command(const RunningServer& server, const std::string& flags) {
  return std::string(PHYSICS_CLIENT_EXE) + " --port " + std::to_string(server.port()) + " " + flags;
}

TEST(Tool, PrintsOneJsonLinePerSnapshot) {
  RunningServer server(test_config(), scene::default_scene());
  const CommandRun run = run_command(client_command(server, "--ticks 5 --json --accel 1,0"));
  ASSERT_EQ(run.exit_code, 0);
  std::size_t snapshots = 0;
  for (const auto& line : run.lines) {
    if (line.rfind("{\"tick\":", 0) == 0) {
      ++snapshots;
      EXPECT_NE(line.find("\"state_hash\":\""), std::string::npos) << line;
      EXPECT_NE(line.find("\"has_own\":true"), std::string::npos) << line;
    }
  }
  EXPECT_EQ(snapshots, 5u);
}

TEST(Tool, RefusedClientExitsNonZeroWithTheServersError) {
  server::ServerConfig config = test_config();
  config.token = "sesame";
  RunningServer server(config, scene::default_scene());
  const CommandRun run = run_command(client_command(server, "--token nope --ticks 1"));
  EXPECT_EQ(run.exit_code, 2);
  std::string all;
  for (const auto& line : run.lines) all += line + "\n";
  EXPECT_NE(all.find("ERROR_BAD_TOKEN"), std::string::npos) << all;
}

TEST(Tool, BotsModeReportsLatencyAndBandwidth) {
  RunningServer server(test_config(), scene::default_scene());
  const CommandRun run = run_command(client_command(server, "--bots 2 --duration 0.5 --json"));
  ASSERT_EQ(run.exit_code, 0);
  ASSERT_FALSE(run.lines.empty());
  const std::string& report = run.lines.back();
  EXPECT_NE(report.find("\"connected\":2"), std::string::npos) << report;
  EXPECT_EQ(report.find("\"latency_samples\":0,"), std::string::npos) << report;
}

}  // namespace
}  // namespace itest
