// Integration tests as a team writing a game on the physics server would write them:
// the server in the test process or as a child process, real clients over loopback
// TCP, and a networked run held to the same world stepped in-process.
#include <gtest/gtest.h>

#include <cmath>

#include "physics_testing/testing.h"

namespace {

using namespace std::chrono_literals;
using physics_testing::InProcessServer;

// The game's arena, built in code: a floor, gravity, two spawn points on it.
scene::SceneDef arena() {
  scene::SceneDef scene;
  scene.name = "arena";
  scene.world.gravity = {0.0, -9.81};
  scene.tick_rate = 60.0;
  scene.max_acceleration = 30.0;
  scene.spawn_points = {{-5.0, 1.0}, {5.0, 1.0}};
  phys::BodyDef floor;
  floor.shape = phys::Shape::Box;
  floor.motion = phys::Motion::Static;
  floor.half_extents = {50.0, 0.5};
  floor.position = {0.0, -0.5};
  scene.bodies.push_back(floor);
  scene.player.shape = phys::Shape::Circle;
  scene.player.motion = phys::Motion::Dynamic;
  scene.player.radius = 0.5;
  scene.player.mass = 1.0;
  return scene;
}

// One player pushes right; both players see that player's body move right.
TEST(GameServer, APlayersPushIsSeenByEveryPlayer) {
  InProcessServer server(arena());
  auto players = physics_testing::connect_clients(server.client_config("player"), 2);
  ASSERT_TRUE(players);
  client::Client& pusher = *(*players)[0];
  client::Client& watcher = *(*players)[1];
  const std::uint64_t body = pusher.welcome().body_id;
  ASSERT_TRUE(pusher.send_input(pusher.welcome().current_tick + 1, 20.0, 0.0));

  double start_x = 0.0;
  for (const client::BodyShape& shape : pusher.welcome().bodies) {
    if (shape.body_id == body) start_x = shape.position.x;
  }
  const auto moved_right = [body, start_x](const client::Snapshot& s) {
    const client::BodyState* b = s.find(body);
    return b != nullptr && b->position.x > start_x + 0.5 && b->velocity.x > 0.0;
  };
  EXPECT_TRUE(physics_testing::wait_for_snapshot(pusher, moved_right, 3s, "the push"));
  EXPECT_TRUE(physics_testing::wait_for_snapshot(watcher, moved_right, 3s, "the other's push"));
}

// In lockstep the server's world equals, hash for hash, the arena stepped here with
// the same inputs.
TEST(GameServer, LockstepRunEqualsTheInProcessWorld) {
  server::ServerConfig config = physics_testing::test_server_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;
  InProcessServer server(arena(), config);
  auto players = physics_testing::connect_clients(server.exact_client_config("p"), 2);
  ASSERT_TRUE(players);
  const auto script = [](std::size_t k, std::uint64_t tick) {
    const double phase = 0.1 * static_cast<double>(tick) + static_cast<double>(k);
    return client::Vec2{8.0 * std::cos(phase), 15.0 * std::sin(phase)};
  };
  const auto run = physics_testing::compare_lockstep_run(arena(), *players, script, 120);
  EXPECT_TRUE(run);
}

// The installed physics-server as a child process, as any language would run it.
TEST(GameServer, TheInstalledServerRunsAsAChildProcess) {
  physics_testing::ProcessOptions options;
  options.executable = PHYSICS_SERVER_EXE;
  physics_testing::ServerProcess process(options);
  client::Client player(process.client_config("jumper"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string() << process.log();
  ASSERT_TRUE(player.send_input(player.welcome().current_tick + 1, 0.0, 25.0));
  EXPECT_TRUE(physics_testing::wait_for_snapshot(
      player, [](const client::Snapshot& s) { return s.own && s.own->velocity.y > 0.0; }, 3s,
      "the player rising"));
  EXPECT_EQ(process.stop(), 0) << process.log();
}

}  // namespace

// The same game over a 100 ms round trip with 0-10 ms of jitter: physics::testing's
// link conditioner between the player and the server.
TEST(GameServer, APlayerFiftyMillisecondsAwayJoinsAndIsServed) {
  InProcessServer server(arena());
  physics_testing::LinkConditionerConfig path_config;
  path_config.target_port = server.port();
  path_config.path = physics_testing::symmetric_path(50ms, 10ms);
  physics_testing::LinkConditioner path(path_config);
  client::ClientConfig config = server.client_config("far-player");
  config.port = path.port();
  client::Client player(config);
  const auto began = std::chrono::steady_clock::now();
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  // Hello up and Welcome back: one round trip at least.
  EXPECT_GE(std::chrono::steady_clock::now() - began, 100ms);
  EXPECT_TRUE(physics_testing::wait_for_snapshot(
      player, [](const client::Snapshot&) { return true; }, 3s, "a snapshot"));
  EXPECT_EQ(path.stats().connections, 1u);
}
