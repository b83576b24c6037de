#pragma once
// A scene of testing/scenes made into a world and stepped for a while at 60 Hz: the
// states the saved-state and rollback benchmarks start from.
#include "physics/world.h"
#include "scenes/scenes.h"

namespace microbench {

inline constexpr double kDt = 1.0 / 60.0;

inline phys::World stepped_world(const scenes::SceneSpec& scene, int presteps) {
  phys::WorldSettings settings;
  settings.gravity = scene.gravity;
  phys::World world(settings);
  scenes::add_to_world(world, scene);
  for (int i = 0; i < presteps; ++i) world.step(kDt);
  return world;
}

}  // namespace microbench
