// compare_lockstep_run: a networked lockstep run equals the in-process world, and a
// world that differs is caught at its first tick, with a message saying where.
#include "physics_testing/lockstep_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "physics_testing/clients.h"
#include "physics_testing/in_process_server.h"

namespace physics_testing {
namespace {

using namespace std::chrono_literals;

client::Vec2 circling(std::size_t k, std::uint64_t t) {
  const double phase = static_cast<double>(t) * 0.21 + static_cast<double>(k) * 1.7;
  return {6.0 * std::cos(phase), 6.0 * std::sin(phase) + 4.0};
}

server::ServerConfig lockstep_config() {
  server::ServerConfig config = test_server_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;  // no tick may be stepped without every input
  return config;
}

TEST(CompareLockstepRun, ThreeClientsOnTheDefaultSceneMatchTheInProcessWorld) {
  const scene::SceneDef scene = scene::default_scene();
  InProcessServer server(scene, lockstep_config());
  Expected<Clients> players = connect_clients(server.exact_client_config("p"), 3);
  ASSERT_TRUE(players);
  const Expected<LockstepRun> run = compare_lockstep_run(scene, *players, circling, 60);
  ASSERT_TRUE(run);
  ASSERT_EQ(run->hashes.size(), 60u);
  // The world moved: a run of one repeated hash would compare nothing.
  EXPECT_GT(std::set<std::uint64_t>(run->hashes.begin(), run->hashes.end()).size(), 50u);
  EXPECT_EQ(server.stats().lockstep_timeouts, 0u);
}

TEST(CompareLockstepRun, AnotherWorldIsCaughtAtTheFirstTickWithTheHashes) {
  InProcessServer server(scene::default_scene(), lockstep_config());
  Expected<Clients> players = connect_clients(server.exact_client_config("p"), 2);
  ASSERT_TRUE(players);
  scene::SceneDef other = scene::default_scene();
  other.world.gravity.y *= 0.5;
  const Expected<LockstepRun> run = compare_lockstep_run(other, *players, circling, 20);
  ASSERT_FALSE(run);
  const std::uint64_t first = (*players)[0]->welcome().current_tick + 1;
  EXPECT_NE(run.message().find("tick " + std::to_string(first) + ", client 0"), std::string::npos)
      << run.message();
  EXPECT_NE(run.message().find("differs from the in-process world's 0x"), std::string::npos)
      << run.message();
}

// A lobby welcomes nobody until every seat is taken: clients that connected one after
// another would wait for each other forever; connect_clients connects them at once.
TEST(CompareLockstepRun, AFullLobbyMatchesTheInProcessWorld) {
  server::ServerConfig config = lockstep_config();
  config.lockstep_players = 3;
  InProcessServer server(scene::default_scene(), config);
  Expected<Clients> players = connect_clients(server.exact_client_config("seat"), 3);
  ASSERT_TRUE(players);
  EXPECT_TRUE(compare_lockstep_run(scene::default_scene(), *players, circling, 30));
}

TEST(CompareLockstepRun, RefusesClientsWithoutTheHashInTheirView) {
  InProcessServer server(scene::default_scene(), lockstep_config());
  Expected<Clients> players = connect_clients(server.client_config("p"), 1);
  ASSERT_TRUE(players);
  const Expected<LockstepRun> run =
      compare_lockstep_run(scene::default_scene(), *players, circling, 5);
  ASSERT_FALSE(run);
  EXPECT_NE(run.message().find("exact_client_config"), std::string::npos) << run.message();
}

TEST(CompareLockstepRun, RefusesAServerThatIsNotInLockstep) {
  InProcessServer server(scene::default_scene());
  Expected<Clients> players = connect_clients(server.exact_client_config("p"), 1);
  ASSERT_TRUE(players);
  const Expected<LockstepRun> run =
      compare_lockstep_run(scene::default_scene(), *players, circling, 5);
  ASSERT_FALSE(run);
  EXPECT_NE(run.message().find("not a player of a lockstep server"), std::string::npos)
      << run.message();
}

}  // namespace
}  // namespace physics_testing
