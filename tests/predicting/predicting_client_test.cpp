// Two PredictingClients playing on a real server through a 50 ms one-way path, in
// lockstep and at a fixed rate: each one's confirmed state equals the server's at
// every tick the relay carries a hash for (every tick here), while the other
// player's input changes make it roll back.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "client/predicting_client.h"
#include "harness.h"
#include "physics_testing/link_conditioner.h"

namespace {

using namespace std::chrono_literals;
using physics_testing::LinkConditioner;

client::PredictingClientConfig player_config(std::uint16_t port, const std::string& name) {
  client::PredictingClientConfig config;
  config.client.port = port;
  config.client.name = name;
  config.client.view.view_hash_interval = 1;  // the state hash with every relayed tick
  config.client.view.window = 64;
  return config;
}

// Player 0 turns every tick (predicted right by itself, wrong by the other); player
// 1 changes its push every 30 ticks.
client::Vec2 push(int player, std::uint64_t tick) {
  if (player == 1) return {(tick / 30) % 2 == 0 ? 6.0 : -6.0, 2.0};
  const double angle = static_cast<double>(tick % 120) * (2.0 * M_PI / 120.0);
  return {5.0 * std::cos(angle), 5.0 * std::sin(angle)};
}

void play_through_a_path(bool lockstep) {
  itest::RunningServer server(itest::test_config(lockstep), scene::default_scene());
  LinkConditioner link(
      physics_testing::relay_to(server.port(), physics_testing::symmetric_path(50ms)));
  std::vector<std::unique_ptr<client::PredictingClient>> players;
  for (int i = 0; i < 2; ++i) {
    players.push_back(std::make_unique<client::PredictingClient>(
        player_config(link.port(), "predicting-" + std::to_string(i))));
    ASSERT_TRUE(players.back()->connect(5s)) << players.back()->error();
  }
  // Both players in turn, a few milliseconds each, for about four seconds.
  const auto end = std::chrono::steady_clock::now() + 4s;
  while (std::chrono::steady_clock::now() < end) {
    for (int i = 0; i < 2; ++i) {
      const auto polled = players[static_cast<std::size_t>(i)]->poll(
          std::chrono::steady_clock::now() + 2ms, [i](std::uint64_t tick) { return push(i, tick); });
      ASSERT_NE(polled, client::PollResult::Ended) << players[static_cast<std::size_t>(i)]->error();
    }
  }
  for (const auto& player : players) {
    const client::PredictionStats& stats = player->core().stats();
    SCOPED_TRACE(player->welcome().body_id);
    EXPECT_GE(stats.confirmed_ticks, 100u);
    // Every confirmed tick carried the server's hash, and every one was ours.
    EXPECT_EQ(stats.hashes_checked, stats.confirmed_ticks);
    EXPECT_EQ(stats.desyncs, 0u) << player->core().error();
    EXPECT_EQ(stats.bad_changes + stats.gaps + stats.stale_ticks + stats.resyncs, 0u)
        << player->core().error();
    EXPECT_GT(player->core().predicted_tick(), player->core().confirmed_tick());
  }
  // The other player's changes were rolled back.
  EXPECT_GE(players[0]->core().stats().rollbacks, 3u);
  EXPECT_GE(players[1]->core().stats().rollbacks, 3u);
}

TEST(PredictingClient, LockstepConfirmedStateIsTheServersThroughA50msPath) {
  play_through_a_path(true);
}

TEST(PredictingClient, FixedRateConfirmedStateIsTheServersThroughA50msPath) {
  play_through_a_path(false);
}

}  // namespace
