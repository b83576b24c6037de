// Warm-start slots: each awake body keeps the impulses of at most kWarmSlots (8)
// contacts it is the lower body of; further contacts start cold, and are counted
// (StageCounters::warm_start_overflows).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics/world.h"

namespace phys::testing {
namespace {

// A circle of radius 2 resting, under gravity, in a cradle of `cradle` static circles
// of radius 0.3 spread over the lower arc. A pair with a static body has the awake
// body as its lower one, so every contact is the big circle's, and each carries
// some of its weight.
StageCounters cradled(int cradle, bool warm_starting) {
  WorldSettings settings;
  settings.warm_starting = warm_starting;
  settings.sleeping = false;
  World world(settings);
  BodyDef big;
  big.shape = Shape::Circle;
  big.radius = 2.0;
  big.mass = 10.0;
  world.add_body(big);
  for (int i = 0; i < cradle; ++i) {
    const double angle = -std::numbers::pi * (20.0 + 140.0 * i / (cradle - 1)) / 180.0;
    BodyDef small;
    small.shape = Shape::Circle;
    small.motion = Motion::Static;
    small.radius = 0.3;
    small.position = Vec2{std::cos(angle), std::sin(angle)} * 2.3;
    world.add_body(small);
  }
  for (int i = 0; i < 30; ++i) world.step(1.0 / 60.0);
  return world.counters();
}

TEST(WarmStartSlots, ContactsPastTheSlotsAreCounted) {
  EXPECT_EQ(cradled(6, true).warm_start_overflows, 0u);
  const StageCounters twelve = cradled(12, true);
  EXPECT_GT(twelve.velocity_solves, 0u);
  EXPECT_GT(twelve.warm_start_overflows, 0u);
  // At most 12 - 8 contacts a sub-step fall past the slots.
  EXPECT_LE(twelve.warm_start_overflows, 4u * twelve.velocity_solves);
  EXPECT_EQ(cradled(12, false).warm_start_overflows, 0u);
}

}  // namespace
}  // namespace phys::testing
