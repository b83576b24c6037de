// In-process servers from a scene in code or a file, N clients at once, and waits
// whose failures say what was seen.
#include "physics_testing/clients.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

#include "physics_testing/in_process_server.h"

namespace physics_testing {
namespace {

using namespace std::chrono_literals;

// Two players far apart in open space, no gravity.
scene::SceneDef open_space() {
  scene::SceneDef scene;
  scene.name = "open-space";
  scene.world.gravity = {0.0, 0.0};
  scene.tick_rate = 60.0;
  scene.max_acceleration = 50.0;
  for (int i = 0; i < 4; ++i) scene.spawn_points.push_back({100.0 * i, 0.0});
  scene.player.shape = phys::Shape::Circle;
  scene.player.motion = phys::Motion::Dynamic;
  scene.player.radius = 0.5;
  scene.player.mass = 1.0;
  return scene;
}

// A test's output holds the server's warnings and errors only: joins and leaves
// (info lines) are not written under test_server_config's level.
TEST(InProcessServer, WritesNoJoinLinesUnderTheTestConfigsLevel) {
  EXPECT_EQ(test_server_config().log_level, server::LogLevel::Warn);
  // spdlog's default logger writes to stdout; physics-server's, to stderr.
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  {
    InProcessServer server(open_space());
    Expected<Clients> clients = connect_clients(server.client_config("quiet"), 1);
    EXPECT_TRUE(clients);
  }
  const std::string written =
      ::testing::internal::GetCapturedStdout() + ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(written.find("joined"), std::string::npos) << written;
}

TEST(InProcessServer, ServesNClientsEachTheirOwnBody) {
  InProcessServer server(open_space());
  ASSERT_NE(server.port(), 0);
  Expected<Clients> clients = connect_clients(server.client_config("player"), 3);
  ASSERT_TRUE(clients);
  std::set<std::uint64_t> bodies;
  for (auto& c : *clients) {
    EXPECT_EQ(c->welcome().scene_name, "open-space");
    bodies.insert(c->welcome().body_id);
    const std::uint64_t own = c->welcome().body_id;
    EXPECT_TRUE(wait_for_snapshot(
        *c, [&](const client::Snapshot& s) { return s.find(own) != nullptr; }, 3s, "the own body"));
  }
  EXPECT_EQ(bodies.size(), 3u);
  EXPECT_TRUE(
      eventually([&] { return server.stats().connected_clients == 3; }, 3s, "3 clients in"));
}

TEST(InProcessServer, AnInputMovesTheOwnBodyAsSeenInASnapshot) {
  InProcessServer server(open_space());
  client::Client player(server.client_config("mover"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  ASSERT_TRUE(player.send_input(player.welcome().current_tick + 1, 10.0, 0.0));
  const auto moving = wait_for_snapshot(
      player, [](const client::Snapshot& s) { return s.own && s.own->velocity.x > 0.0; }, 3s,
      "the own body moving in +x");
  ASSERT_TRUE(moving);
  double spawn_x = 0.0;
  for (const client::BodyShape& body : player.welcome().bodies) {
    if (body.body_id == player.welcome().body_id) spawn_x = body.position.x;
  }
  EXPECT_GT(moving->own->position.x, spawn_x);
  EXPECT_EQ(moving->own->velocity.y, 0.0);
}

TEST(InProcessServer, ServesASceneFile) {
  const std::filesystem::path file = PHYSICS_SCENES_DIR "/box-pyramid.textproto";
  const Expected<scene::SceneDef> scene = load_scene(file);
  ASSERT_TRUE(scene);
  InProcessServer server(file);
  EXPECT_EQ(server.scene().name, scene->name);
  client::Client player(server.client_config());
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  EXPECT_EQ(player.welcome().scene_name, scene->name);
}

TEST(InProcessServer, ABadSceneFileIsAnErrorNamingTheFile) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "physics-testing-bad-scene.textproto";
  std::ofstream(file) << "tick_rate: \"fast\"\n";
  try {
    InProcessServer server(file);
    FAIL() << "a bad scene file was served";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("physics-testing-bad-scene.textproto"),
              std::string::npos)
        << error.what();
  }
  std::filesystem::remove(file);
  EXPECT_FALSE(load_scene("/nonexistent/scene.textproto"));
}

TEST(ConnectClients, SaysWhichClientsWereRefusedAndWhy) {
  server::ServerConfig config = test_server_config();
  config.max_clients = 1;
  InProcessServer server(open_space(), config);
  const Expected<Clients> clients = connect_clients(server.client_config("crowd"), 2);
  ASSERT_FALSE(clients);
  EXPECT_NE(clients.message().find("not every client connected (2 asked for)"), std::string::npos)
      << clients.message();
  EXPECT_NE(clients.message().find("ERROR_SERVER_FULL"), std::string::npos) << clients.message();
}

TEST(WaitForSnapshot, ATimeoutSaysWhatWasAwaitedAndSeen) {
  InProcessServer server(open_space());
  client::Client player(server.client_config());
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  const auto never = wait_for_snapshot(
      player, [](const client::Snapshot&) { return false; }, 300ms, "a miracle");
  ASSERT_FALSE(never);
  EXPECT_NE(never.message().find("no snapshot with a miracle within 300 ms"), std::string::npos)
      << never.message();
  EXPECT_NE(never.message().find("the last at tick"), std::string::npos) << never.message();
}

TEST(WaitForSnapshot, SaysWhyTheSessionEnded) {
  auto server = std::make_unique<InProcessServer>(open_space());
  client::Client player(server->client_config());
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  server->stop();
  const auto after = wait_for_snapshot(
      player, [](const client::Snapshot&) { return false; }, 3s, "anything");
  ASSERT_FALSE(after);
  EXPECT_NE(after.message().find("client: "), std::string::npos) << after.message();
}

TEST(Eventually, AFailureNamesTheCondition) {
  const Outcome outcome = eventually([] { return false; }, 20ms, "the moon turning blue");
  ASSERT_FALSE(outcome);
  EXPECT_EQ(outcome.message(), "the moon turning blue did not hold within 20 ms");
  EXPECT_TRUE(eventually([] { return true; }, 0ms));
}

}  // namespace
}  // namespace physics_testing
