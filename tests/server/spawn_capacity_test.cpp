// How many players the built-in scene fits before ERROR_NO_SPAWN: the figure
// physics-server --help and docs/SERVER.md state beside --max-clients (64).
#include <gtest/gtest.h>

#include "scene/scene.h"
#include "server/simulation.h"

namespace {

TEST(SpawnCapacity, TheBuiltInSceneFits58PlayersJoiningAtTick0) {
  server::Simulation simulation(scene::default_scene());
  server::ClientId client = 1;
  while (simulation.join(client)) ++client;
  EXPECT_EQ(client - 1, 58u);
  EXPECT_EQ(simulation.room().size(), 58u);
}

}  // namespace
