// Spectators: clients that watch without a body. They see every body, add none,
// are counted and limited apart from the players, and never hold up a lockstep tick.
#include <gtest/gtest.h>

#include "harness.h"
#include "test_scenes.h"

namespace itest {
namespace {

client::ClientConfig spectator_config(const RunningServer& server, const std::string& name) {
  client::ClientConfig config = server.exact_client_config(name);
  config.spectate = true;
  return config;
}

TEST(Spectator, WatchesEveryBodyWithoutAddingOne) {
  RunningServer server(test_config(), scene::default_scene());
  client::Client player(server.exact_client_config("player"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  client::Client watcher(spectator_config(server, "watcher"));
  ASSERT_TRUE(watcher.connect(3s)) << watcher.last_error().to_string();
  EXPECT_TRUE(watcher.welcome().spectator);
  EXPECT_EQ(watcher.welcome().body_id, 0u);
  // The Welcome lists the world as the player's did: the spectator added no body.
  EXPECT_EQ(watcher.welcome().bodies.size(), player.welcome().bodies.size());
  ASSERT_TRUE(player.send_input(player.welcome().current_tick + 1, 5.0, 0.0));
  auto seen = watcher.wait_for_snapshot(
      3s, [&](const client::Snapshot& s) { return s.find(player.welcome().body_id) != nullptr; });
  ASSERT_TRUE(seen.has_value()) << watcher.last_error().to_string();
  EXPECT_FALSE(seen->own.has_value());
  const auto played =
      player.wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.tick >= seen->tick; });
  ASSERT_TRUE(played.has_value());
  auto watched = watcher.wait_for_snapshot(
      3s, [&](const client::Snapshot& s) { return s.tick >= played->tick; });
  ASSERT_TRUE(watched.has_value());
  EXPECT_EQ(watched->bodies.size(), played->bodies.size());
  EXPECT_TRUE(eventually([&] {
    const auto stats = server.stats();
    return stats.connected_clients == 1 && stats.spectators == 1;
  }));
}

TEST(Spectator, SpectatorsHaveTheirOwnLimitAndCannotSendInputs) {
  server::ServerConfig config = test_config();
  config.max_spectators = 1;
  config.max_clients = 1;
  RunningServer server(config, scene::default_scene());
  client::Client first(spectator_config(server, "first"));
  ASSERT_TRUE(first.connect(3s)) << first.last_error().to_string();
  client::Client second(spectator_config(server, "second"));
  EXPECT_FALSE(second.connect(3s));
  ASSERT_TRUE(second.last_error().server.has_value());
  EXPECT_EQ(second.last_error().server->code, client::ErrorCode::ServerFull);
  // The player's seat is not taken by the spectator.
  client::Client player(server.client_config("player"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  ASSERT_TRUE(first.send_input(first.welcome().current_tick + 1, 1.0, 0.0));
  auto error = first.next_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code, client::ErrorCode::SpectatorInput);
  EXPECT_FALSE(error->fatal);
  EXPECT_EQ(first.state(), client::ConnectionState::Connected);
}

TEST(Spectator, ARadiusNeedsABodyButARectangleWatchesPartOfTheWorld) {
  RunningServer server(test_config(), scene::default_scene());
  client::ClientConfig around = spectator_config(server, "around");
  around.view.interest_radius = 5.0;
  client::Client radius(around);
  EXPECT_FALSE(radius.connect(3s));
  ASSERT_TRUE(radius.last_error().server.has_value());
  EXPECT_EQ(radius.last_error().server->code, client::ErrorCode::InvalidView);
  client::ClientConfig boxed = spectator_config(server, "boxed");
  boxed.view.interest_rect = client::Rect{-1000.0, -1000.0, 0.0, 1000.0};
  client::Client rect(boxed);
  ASSERT_TRUE(rect.connect(3s)) << rect.last_error().to_string();
  auto snapshot = rect.next_snapshot(3s);
  ASSERT_TRUE(snapshot.has_value());
  // The world has dynamic bodies on both sides of x = 0; only the left ones are sent.
  std::size_t left = 0;
  std::size_t right = 0;
  for (const client::BodyShape& body : rect.welcome().bodies) {
    if (!body.is_static) ++(body.position.x <= 0.0 ? left : right);
  }
  ASSERT_GT(left, 0u);
  ASSERT_GT(right, 0u);
  EXPECT_FALSE(snapshot->bodies.empty());
  for (const client::BodyState& body : snapshot->bodies) EXPECT_LE(body.position.x, 0.0);
}

TEST(Spectator, ASpectatorNeverHoldsUpALockstepTick) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;  // a tick stepped without its inputs would show
  RunningServer server(config, scene::default_scene());
  client::Client player(server.exact_client_config("player"));
  ASSERT_TRUE(player.connect(3s));
  client::Client watcher(spectator_config(server, "watcher"));
  ASSERT_TRUE(watcher.connect(3s));
  const std::uint64_t start = player.welcome().current_tick;
  for (std::uint64_t t = start + 1; t <= start + 30; ++t) {
    ASSERT_TRUE(player.send_input(t, 2.0, 0.0));
    auto played = player.next_snapshot(2s);
    ASSERT_TRUE(played.has_value()) << "tick " << t;
    ASSERT_EQ(played->tick, t);
    auto watched = watcher.next_snapshot(2s);
    ASSERT_TRUE(watched.has_value()) << "tick " << t;
    EXPECT_EQ(watched->tick, t);
    EXPECT_EQ(watched->state_hash, played->state_hash);
  }
  EXPECT_EQ(server.stats().lockstep_timeouts, 0u);
}

}  // namespace
}  // namespace itest
