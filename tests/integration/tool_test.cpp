// physics-client, the executable, against a real server: it prints one line per
// snapshot (JSON with --json), runs in lockstep to a golden state hash, and exits
// non-zero with the server's error when it is refused.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>

#include "harness.h"
#include "physics/world.h"
#include "scene/scene.h"

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

// Text lines name the state hash only when it was asked for (--state-hash): without
// it the server sends none, and a hash of zeros would read as one.
TEST(Tool, TextLinesShowTheHashOnlyWhenAskedFor) {
  RunningServer server(test_config(), scene::default_scene());
  for (const bool asked : {false, true}) {
    const CommandRun run = run_command(client_command(
        server, std::string("--ticks 3 --accel 1,0") + (asked ? " --state-hash" : "")));
    ASSERT_EQ(run.exit_code, 0);
    std::size_t snapshots = 0;
    for (const auto& line : run.lines) {
      if (line.rfind("tick ", 0) != 0) continue;
      ++snapshots;
      EXPECT_EQ(line.find(" hash ") != std::string::npos, asked) << line;
      EXPECT_EQ(line.find("hash 0000000000000000"), std::string::npos) << line;
    }
    EXPECT_EQ(snapshots, 3u);
  }
}

// The state hash of the last snapshot line of a --json run ("" when there is none).
std::string last_state_hash(const CommandRun& run) {
  const std::string key = "\"state_hash\":\"";
  std::string hash;
  for (const auto& line : run.lines) {
    const std::size_t at = line.rfind("{\"tick\":", 0) == 0 ? line.find(key) : std::string::npos;
    if (at != std::string::npos) hash = line.substr(at + key.size(), 16);
  }
  return hash;
}

std::string hex16(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << value;
  return out.str();
}

// In lockstep a tick waits for the client's input, so a run of physics-client is
// reproducible bit for bit: two runs against two fresh servers end at the same
// hash. That hash is also held to a plain phys::World stepped with the same input
// (the player's body added as the room adds it: the player template at the first
// spawn point) and to a golden value, so that the two runs cannot drift together.
TEST(Tool, LockstepRunEndsAtTheSameHashTwiceAndAtTheGolden) {
  constexpr int kTicks = 30;
  auto run_once = [] {
    RunningServer server(test_config(true), scene::default_scene());
    return run_command(client_command(
        server, "--ticks " + std::to_string(kTicks) + " --json --accel 2,0 --state-hash"));
  };
  const CommandRun first = run_once();
  const CommandRun second = run_once();
  ASSERT_EQ(first.exit_code, 0);
  ASSERT_EQ(second.exit_code, 0);
  const std::string hash = last_state_hash(first);
  ASSERT_EQ(hash.size(), 16u);
  EXPECT_EQ(last_state_hash(second), hash);

  const scene::SceneDef& scene = scene::default_scene();
  phys::World world = scene::build_world(scene);
  phys::BodyDef player = scene.player;
  player.motion = phys::Motion::Dynamic;
  player.position = scene.spawn_points[0];
  const phys::BodyId body = world.add_body(player);
  for (int tick = 1; tick <= kTicks; ++tick) {
    world.set_acceleration(body, {2.0, 0.0});  // the input of tick t, during step t
    world.step(1.0 / scene.tick_rate);
  }
  EXPECT_EQ(hash, hex16(world.state_hash())) << "a plain World with the same input";
  // Golden: the default scene's state hash after 30 lockstep ticks of one client
  // pushing (2, 0) m/s^2, measured once. The hash is promised to be the same for
  // every compiler and build type; a change of it means the results changed (of
  // the step, the scene, or how the server applies inputs), and the change that
  // does it must say so and update this value.
  EXPECT_EQ(hash, "b060c2e0cda0b79f");
}

TEST(Tool, RefusedClientExitsNonZeroWithTheServersError) {
  server::ServerConfig config = test_config();
  config.token = "sesame";
  RunningServer server(config, scene::default_scene());
  const CommandRun run = run_command(client_command(server, "--token nope --ticks 1"));
  EXPECT_EQ(run.exit_code, 1);
  std::string all;
  for (const auto& line : run.lines) all += line + "\n";
  EXPECT_NE(all.find("ERROR_BAD_TOKEN"), std::string::npos) << all;
}

TEST(Tool, SeatFlagAsksForThatSeat) {
  server::ServerConfig config = test_config();
  config.max_clients = 2;
  RunningServer server(config, scene::default_scene());
  const CommandRun taken = run_command(client_command(server, "--seat 2 --ticks 1"));
  EXPECT_EQ(taken.exit_code, 1);
  std::string all;
  for (const auto& line : taken.lines) all += line + "\n";
  EXPECT_NE(all.find("ERROR_SEAT_OUT_OF_RANGE"), std::string::npos) << all;
  EXPECT_EQ(run_command(client_command(server, "--seat 1 --ticks 1")).exit_code, 0);
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
