// Goal rush predicted: two players whose clients run the game's rules in their
// prediction (client::PredictingClientConfig::rules, the same GoalRushRules the
// server runs), and a thin spectator, all through a 50 ms one-way path, in lockstep
// and at a fixed rate. The players jump and shoot (game messages) while they run:
// each one's own messages are in its next predicted tick, the other's roll it back,
// and its confirmed state, the game's state included, is the server's at every tick.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/predicting_client.h"
#include "goal_rush_rules.h"
#include "physics_testing/testing.h"

namespace {

using namespace std::chrono_literals;

scene::SceneDef goal_rush_scene() {
  physics_testing::Expected<scene::SceneDef> scene = physics_testing::load_scene(GOAL_RUSH_SCENE);
  if (!scene) throw std::runtime_error(scene.message());
  return *scene;
}

client::PredictingClientConfig player_config(std::uint16_t port, const std::string& name,
                                             const scene::SceneDef& scene) {
  client::PredictingClientConfig config;
  config.client.port = port;
  config.client.name = name;
  config.client.view.view_hash_interval = 1;  // the state hash with every relayed tick
  config.client.view.window = 64;
  config.rules = std::make_shared<goal_rush::GoalRushRules>(scene.player);
  return config;
}

// Each player runs one way and back, and jumps and shoots on its own beat.
client::Vec2 run(int player, std::uint64_t tick) {
  const bool right = ((tick + static_cast<std::uint64_t>(player) * 20) / 45) % 2 == 0;
  return {right ? 8.0 : -8.0, 0.0};
}
std::string message(int player, std::uint64_t tick) {
  const std::uint64_t beat = tick + static_cast<std::uint64_t>(player) * 11;
  if (beat % 37 == 0) return "shoot";
  if (beat % 23 == 0) return "jump";
  return {};
}

void play(bool lockstep) {
  const scene::SceneDef scene = goal_rush_scene();
  server::ServerConfig config = physics_testing::test_server_config(lockstep);
  config.rules = std::make_shared<goal_rush::GoalRushRules>(scene.player);
  physics_testing::InProcessServer server(scene, config);
  physics_testing::LinkConditioner link(
      physics_testing::relay_to(server.port(), physics_testing::symmetric_path(50ms)));

  std::vector<std::unique_ptr<client::PredictingClient>> players;
  for (int i = 0; i < 2; ++i) {
    players.push_back(std::make_unique<client::PredictingClient>(
        player_config(link.port(), "player-" + std::to_string(i), scene)));
    ASSERT_TRUE(players.back()->connect(5s)) << players.back()->error();
    EXPECT_TRUE(players.back()->welcome().rules_run_here);
  }
  client::ClientConfig watcher = server.exact_client_config("thin-spectator");
  watcher.port = link.port();
  watcher.spectate = true;
  client::Client thin(watcher);
  ASSERT_TRUE(thin.connect(5s)) << thin.last_error().to_string();

  std::uint64_t sent[2] = {0, 0};
  std::uint64_t shown_at_once[2] = {0, 0};
  const auto end = std::chrono::steady_clock::now() + 5s;
  while (std::chrono::steady_clock::now() < end) {
    for (int i = 0; i < 2; ++i) {
      client::PredictingClient& player = *players[static_cast<std::size_t>(i)];
      const auto input = [&](std::uint64_t tick) {
        if (const std::string payload = message(i, tick); !payload.empty()) {
          if (player.send_game_message(tick, payload)) ++sent[i];
        }
        return run(i, tick);
      };
      const std::uint64_t before = player.core().predicted_tick();
      const client::PollResult polled = player.poll(std::chrono::steady_clock::now() + 2ms, input);
      ASSERT_NE(polled, client::PollResult::Ended) << player.error();
      // The prediction stands at the newest tick sent: every message sent is in it.
      if (polled == client::PollResult::InputSent && player.pacer() != nullptr &&
          player.core().predicted_tick() == player.pacer()->last_sent() &&
          player.core().predicted_tick() > before) {
        ++shown_at_once[i];
      }
    }
    while (thin.next_snapshot(1ms)) {
    }
  }
  for (int i = 0; i < 2; ++i) {
    const client::PredictingClient& player = *players[static_cast<std::size_t>(i)];
    const client::PredictionStats& stats = player.core().stats();
    SCOPED_TRACE("player " + std::to_string(i));
    EXPECT_GE(sent[i], 5u);
    EXPECT_GT(shown_at_once[i], 100u);
    EXPECT_GE(stats.confirmed_ticks, 150u);
    // Every confirmed tick carried the server's hash (the game's state in it), and
    // every one was ours.
    EXPECT_EQ(stats.hashes_checked, stats.confirmed_ticks);
    EXPECT_EQ(stats.desyncs, 0u) << player.core().error();
    EXPECT_EQ(
        stats.bad_changes + stats.gaps + stats.stale_ticks + stats.resyncs + stats.rules_errors, 0u)
        << player.core().error();
    // The other player's moves and messages were rolled back.
    EXPECT_GE(stats.rollbacks, 3u);
  }
  EXPECT_GT(thin.stats().snapshots_received, 150u);
  EXPECT_EQ(thin.stats().desyncs, 0u);
}

TEST(GoalRushPredicted, LockstepEveryClientHoldsTheServersStateThroughA50msPath) { play(true); }

TEST(GoalRushPredicted, FixedRateEveryClientHoldsTheServersStateThroughA50msPath) { play(false); }

}  // namespace
