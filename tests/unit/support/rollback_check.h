#pragma once
// The save/restore check of a world (World::save, World::restore): saved at one
// step, stepped on, restored, and stepped on again, the world must take exactly the
// steps it took the first time; and a fresh World built from the saved state must
// take them too. Shared by the scene library's suite and the scene files' suite.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "physics/world.h"

namespace phys::testing {

// Steps `world` `steps` times at `dt`, returning the state hash after each step.
inline std::vector<std::uint64_t> hashes_of_steps(World& world, int steps, double dt) {
  std::vector<std::uint64_t> hashes;
  hashes.reserve(static_cast<std::size_t>(steps));
  for (int i = 0; i < steps; ++i) {
    world.step(dt);
    hashes.push_back(world.state_hash());
  }
  return hashes;
}

// `world` is at the step to save at. Leaves it `steps` steps later.
inline void expect_restore_replays(World& world, int steps, double dt) {
  const SavedWorld saved = world.save();
  ASSERT_FALSE(saved.empty());
  EXPECT_EQ(saved.step_count(), world.step_count());
  const std::uint64_t saved_hash = world.state_hash();
  const std::size_t awake_at_save = world.awake_body_count();
  const std::vector<std::uint64_t> first = hashes_of_steps(world, steps, dt);
  const std::size_t awake_after = world.awake_body_count();

  world.restore(saved);
  EXPECT_EQ(world.state_hash(), saved_hash);
  EXPECT_EQ(world.step_count(), saved.step_count());
  EXPECT_EQ(world.awake_body_count(), awake_at_save);
  EXPECT_EQ(hashes_of_steps(world, steps, dt), first) << "restored, then stepped";
  EXPECT_EQ(world.awake_body_count(), awake_after);

  World fresh(saved);
  EXPECT_EQ(fresh.state_hash(), saved_hash);
  EXPECT_EQ(fresh.body_count(), world.body_count());
  const std::vector<std::uint8_t> bytes = fresh.to_bytes();
  EXPECT_EQ(hashes_of_steps(fresh, steps, dt), first) << "a fresh World from the saved state";

  // The same state through bytes (World::to_bytes, World::from_bytes), as a client
  // in another process gets it.
  std::string error;
  std::optional<World> loaded = World::from_bytes(bytes, &error);
  ASSERT_TRUE(loaded.has_value()) << error;
  EXPECT_EQ(loaded->to_bytes(), bytes) << "read and written again, the bytes are the same";
  EXPECT_EQ(loaded->state_hash(), saved_hash);
  EXPECT_EQ(loaded->step_count(), saved.step_count());
  EXPECT_EQ(hashes_of_steps(*loaded, steps, dt), first) << "a World read from the bytes";
}

}  // namespace phys::testing
