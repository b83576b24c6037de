// Goal rush served by physics-server itself, its rules loaded from the library
// (physics-server --rules libgoal_rush.so), as a game team ships it: two players over
// TCP in lockstep, a jump asked for by a game message, a goal heard by the other
// player, and every tick's state hash equal to the same rules run in-process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "goal_rush_rules.h"
#include "physics_testing/testing.h"

namespace {

using namespace std::chrono_literals;
using physics_testing::GameRun;

constexpr std::uint64_t kTicks = 90;
constexpr std::uint64_t kJumpTick = 40;  // the left player is resting on the ground by then

// Goal rush's scene with the ball dropped above the left goal, so that a goal comes
// within the run: the right player scores, and both hear it.
std::filesystem::path scene_with_ball_over_left_goal() {
  std::ifstream in(GOAL_RUSH_SCENE);
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const std::string ball_start = "position { x: 0 y: 8 }";
  const std::size_t at = scene.find(ball_start);
  if (at == std::string::npos) throw std::runtime_error("the scene's ball is not at (0, 8)");
  scene.replace(at, ball_start.size(), "position { x: -14 y: 5 }");
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("goal-rush-plugin-test-" + std::to_string(getpid()) + ".textproto");
  std::ofstream(file) << scene;
  return file;
}

client::Vec2 steer(std::size_t player, std::uint64_t tick) {
  if (player == 0) return {tick < 30 ? 10.0 : -10.0, 0.0};
  return {-5.0, 0.0};
}

// The rules in-process, stepped as the server steps them: the same joins, the same
// input for each tick, the jump at kJumpTick.
std::vector<physics_testing::GameTick> in_process_run(const scene::SceneDef& scene) {
  GameRun run(scene, std::make_shared<goal_rush::GoalRushRules>(scene.player));
  const auto left = run.join();
  const auto right = run.join();
  if (!left || !right) throw std::runtime_error("in-process: the players could not join");
  const server::ClientId players[] = {*left, *right};
  for (std::uint64_t tick = 1; tick <= kTicks; ++tick) {
    for (std::size_t k = 0; k < 2; ++k) {
      const client::Vec2 a = steer(k, tick);
      if (!run.input(players[k], a.x, a.y)) throw std::runtime_error("in-process input");
    }
    if (tick == kJumpTick && !run.message(players[0], "jump")) {
      throw std::runtime_error("in-process jump");
    }
    run.step();
  }
  return run.history();
}

TEST(GoalRushPlugin, PhysicsServerServesTheRulesLibraryTickForTickAsInProcess) {
  const std::filesystem::path scene_file = scene_with_ball_over_left_goal();
  physics_testing::ProcessOptions options;
  options.executable = PHYSICS_SERVER_EXE;
  options.scene_file = scene_file;
  // Lockstep, and a timeout no run reaches: every tick waits for both players.
  options.extra_args = {"--rules", GOAL_RUSH_PLUGIN, "--lockstep", "--lockstep-timeout-ms",
                        "600000"};
  physics_testing::ServerProcess server(options);
  const auto scene = physics_testing::load_scene(scene_file);
  std::filesystem::remove(scene_file);
  ASSERT_TRUE(scene);
  const std::vector<physics_testing::GameTick> expected = in_process_run(*scene);

  // One after the other, so that the left player is client 1 as in-process.
  std::vector<std::unique_ptr<client::Client>> players;
  for (const char* name : {"left", "right"}) {
    players.push_back(std::make_unique<client::Client>(server.exact_client_config(name)));
    ASSERT_TRUE(players.back()->connect(5s)) << players.back()->last_error().to_string() << "\n"
                                             << server.log();
    ASSERT_EQ(players.back()->welcome().current_tick, 0u);
  }
  const std::uint64_t left_body = players[0]->welcome().body_id;

  std::vector<std::string> heard_by_left;
  std::vector<client::GameMessage> heard_by_right;
  double vy_before_jump = 0.0;
  for (std::uint64_t tick = 1; tick <= kTicks; ++tick) {
    if (tick == kJumpTick) {
      ASSERT_TRUE(players[0]->send_game_message(tick, "jump"));
    }
    for (std::size_t k = 0; k < 2; ++k) {
      const client::Vec2 a = steer(k, tick);
      ASSERT_TRUE(players[k]->send_input(tick, a.x, a.y));
    }
    const physics_testing::GameTick& reference = expected[tick - 1];
    ASSERT_EQ(reference.tick, tick);
    for (std::size_t k = 0; k < 2; ++k) {
      const auto snapshot = physics_testing::wait_for_snapshot(
          *players[k], [tick](const client::Snapshot& s) { return s.tick >= tick; }, 5s,
          "tick " + std::to_string(tick));
      ASSERT_TRUE(snapshot) << server.log();
      ASSERT_EQ(snapshot->tick, tick);
      ASSERT_EQ(snapshot->state_hash, reference.state_hash) << "tick " << tick << ", player " << k;
      if (k == 0) {
        ASSERT_TRUE(snapshot->own);
        ASSERT_EQ(snapshot->own->body_id, left_body);
        if (tick == kJumpTick - 1) vy_before_jump = snapshot->own->velocity.y;
        // The jump sets the body's vertical speed at the very tick it was sent for.
        if (tick == kJumpTick) {
          EXPECT_LT(std::abs(vy_before_jump), 0.05);
          EXPECT_GT(snapshot->own->velocity.y, goal_rush::kJumpSpeed - 0.5);
        }
      }
    }
  }
  for (const client::GameMessage& message : players[1]->take_game_messages()) {
    heard_by_right.push_back(message);
  }
  for (const client::GameMessage& message : players[0]->take_game_messages()) {
    heard_by_left.push_back(message.payload);
  }

  // The goal of the in-process run, at its tick, reached both players.
  const auto goal =
      std::find_if(expected.begin(), expected.end(),
                   [](const physics_testing::GameTick& t) { return !t.messages.empty(); });
  ASSERT_NE(goal, expected.end()) << "no goal in-process within " << kTicks << " ticks";
  ASSERT_EQ(goal->messages.size(), 1u);
  EXPECT_EQ(goal->messages[0].payload, "score 0 1");
  ASSERT_EQ(heard_by_right.size(), 1u);
  EXPECT_EQ(heard_by_right[0].payload, "score 0 1");
  EXPECT_EQ(heard_by_right[0].tick, goal->tick);
  EXPECT_EQ(heard_by_left, std::vector<std::string>{"score 0 1"});
  EXPECT_EQ(server.stop(), 0) << server.log();
  EXPECT_NE(server.log().find("with game rules"), std::string::npos) << server.log();
}

}  // namespace
