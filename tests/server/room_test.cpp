// Joining gives each client its own body at a free spawn position; leaving removes it.
#include "server/room.h"

#include <gtest/gtest.h>

#include "server/spawn.h"
#include "test_scene.h"

namespace {

using server::Room;

TEST(Room, ClientsGetBodiesAtSpawnPointsInJoinOrder) {
  const scene::SceneDef scene = server_test::free_space_scene();
  phys::World world = scene::build_world(scene);
  Room room;
  const auto a = room.join(7, scene, world);
  const auto b = room.join(3, scene, world);
  ASSERT_TRUE(a && b);
  EXPECT_NE(*a, *b);
  EXPECT_EQ(world.body(*a)->position.x, 0.0);   // first free: spawn 0
  EXPECT_EQ(world.body(*b)->position.x, 10.0);  // spawn 0 is taken by a: spawn 1
  EXPECT_EQ(world.body(*a)->motion, phys::Motion::Dynamic);
  EXPECT_EQ(world.body(*a)->shape, phys::Shape::Circle);
  EXPECT_EQ(room.size(), 2u);
  EXPECT_EQ(room.body_of(7), a);
  EXPECT_EQ(room.body_of(3), b);
}

TEST(Room, LeavingRemovesTheBodyAndFreesItsSpawnPoint) {
  const scene::SceneDef scene = server_test::free_space_scene();
  phys::World world = scene::build_world(scene);
  Room room;
  const auto a = room.join(1, scene, world);
  ASSERT_TRUE(a);
  ASSERT_EQ(world.body_count(), 1u);
  EXPECT_TRUE(room.leave(1, world));
  EXPECT_FALSE(world.contains(*a));
  EXPECT_EQ(world.body_count(), 0u);
  EXPECT_FALSE(room.body_of(1).has_value());
  EXPECT_FALSE(room.leave(1, world));  // twice is a no-op
  const auto again = room.join(2, scene, world);
  ASSERT_TRUE(again);
  EXPECT_EQ(world.body(*again)->position.x, 0.0);
}

TEST(Room, JoiningTwiceIsRefused) {
  const scene::SceneDef scene = server_test::free_space_scene();
  phys::World world = scene::build_world(scene);
  Room room;
  ASSERT_TRUE(room.join(1, scene, world));
  EXPECT_FALSE(room.join(1, scene, world));
  EXPECT_EQ(world.body_count(), 1u);
}

TEST(Room, WhenSpawnPointsAreTakenRingsAroundThemAreUsedThenNone) {
  scene::SceneDef scene = server_test::free_space_scene();
  scene.spawn_points = {{0.0, 0.0}};
  phys::World world = scene::build_world(scene);
  Room room;
  // One spawn point, 4 rings of 8 positions each around it: 33 places in all.
  const int places = 1 + server::kSpawnRings * 8;
  for (int i = 0; i < places; ++i) {
    ASSERT_TRUE(room.join(static_cast<server::ClientId>(i), scene, world)) << i;
  }
  EXPECT_FALSE(room.join(1000, scene, world));
  // No two bodies overlap.
  const auto bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      const phys::Vec2 d = bodies[i].position - bodies[j].position;
      EXPECT_GT(phys::length(d), 1.0) << i << " " << j;
    }
  }
}

TEST(Room, SpawnAvoidsBodiesOfTheScene) {
  scene::SceneDef scene = server_test::scene_with_unowned_box();
  scene.spawn_points = {{-10.0, 0.0}, {5.0, 0.0}};  // the first is inside the box
  phys::World world = scene::build_world(scene);
  Room room;
  const auto body = room.join(1, scene, world);
  ASSERT_TRUE(body);
  EXPECT_EQ(world.body(*body)->position.x, 5.0);
}

}  // namespace
