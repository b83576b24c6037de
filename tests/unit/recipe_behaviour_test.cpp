// Behaviours of the step that the golden hashes also pin, checked by what a player
// would see, so that regenerating the goldens cannot ship a change to them: a circle
// resting on an awake box stays on top of it; a box moving diagonally into a step
// is resolved on Y before X, as the recipe orders the phases; a body falls asleep
// after sleep_time still, and one faster than sleep_speed never does.
#include <gtest/gtest.h>

#include <cmath>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

// A circle resting on a dynamic box that never sleeps (the pair goes through the
// circle-and-box contact with the box first, the lower body): the contact's normal
// points from the box up to the circle, so the circle is held on top. Bound: over
// 2 s the circle stays within 1 cm of resting on the box's top face, the box within
// 1 cm of resting on the floor.
TEST(RecipeBehaviour, ACircleOnAnAwakeDynamicBoxStaysOnTop) {
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  add_or_fail(world, box_def({0.0, -0.5}, {10.0, 0.5}, Motion::Static));
  const BodyId box = add_or_fail(world, box_def({0.0, 0.5}, {0.5, 0.5}));
  const BodyId circle = add_or_fail(world, circle_def({0.0, 1.25}, 0.25));
  double worst_circle = 0.0;
  double worst_box = 0.0;
  for (int step = 0; step < 120; ++step) {
    world.step(kDt);
    worst_circle = std::fmax(worst_circle, std::fabs(world.body(circle)->position.y - 1.25));
    worst_box = std::fmax(worst_box, std::fabs(world.body(box)->position.y - 0.5));
  }
  EXPECT_TRUE(world.body(box)->awake);
  EXPECT_LE(worst_circle, 0.01);
  EXPECT_LE(worst_box, 0.01);
}

// A box moving right and down (0.1 m and about 0.2 m a tick) next to a step whose
// top is below the box's bottom. Moving on Y first, the box passes beside the step
// (no overlap on X yet); then moving on X, it meets the step's side and stops there.
// Had X come first, it would have cleared the step's top on X and landed on it on Y.
// Bound: after the first tick its x velocity is 0 and its right face at the step's
// left face; one second later it stands on the floor beside the step.
TEST(RecipeBehaviour, ABoxMovingIntoAStepIsResolvedOnYBeforeX) {
  World world;
  add_or_fail(world, box_def({0.0, -0.5}, {10.0, 0.5}, Motion::Static));  // floor, top 0
  add_or_fail(world,
              box_def({2.0, 0.25}, {1.45, 0.25}, Motion::Static));  // step [0.55, 3.45] x [0, 0.5]
  BodyDef def = box_def({0.0, 1.05}, {0.5, 0.5});
  def.velocity = {6.0, -12.0};
  const BodyId box = add_or_fail(world, def);
  world.step(kDt);
  const BodyState after = *world.body(box);
  EXPECT_LT(after.position.y, 1.05 - 0.15) << "the Y move came first, unhindered";
  EXPECT_EQ(after.velocity.x, 0.0) << "stopped on X by the step's side";
  EXPECT_LE(after.position.x + 0.5, 0.55 + 1e-9);
  EXPECT_NE(after.velocity.y, 0.0);
  for (int step = 0; step < 60; ++step) world.step(kDt);
  const BodyState later = *world.body(box);
  EXPECT_LE(later.position.x + 0.5, 0.55 + 1e-9) << "beside the step";
  EXPECT_NEAR(later.position.y, 0.5, 0.01) << "on the floor, not on the step";
}

// Lone bodies in a world without gravity: a body's stillness window starts at its
// first step (a new body's window is anchored at the origin, so that step moves the
// anchor to it), and its still time then grows by the step's dt each step while it
// stays within sleep_speed * sleep_time of the anchor. At rest, or slower than
// sleep_speed, it is ready once still for sleep_time: awake after step 30 at 60 Hz
// (29 still steps), asleep after step 32 at the latest (30 still steps, 0.5 s, give
// or take the rounding of their sum). Faster than sleep_speed (1.5 times: slower than
// twice it), it leaves that radius within every window and is never asleep.
TEST(RecipeBehaviour, ABodyFallsAsleepAtSleepTimeAndOneFasterThanSleepSpeedNever) {
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  World world(settings);
  const double v = settings.sleep_speed;
  const BodyId resting = add_or_fail(world, circle_def({5.0, 0.0}, 0.5));
  BodyDef slow = circle_def({0.0, 10.0}, 0.5);
  slow.velocity = {0.5 * v, 0.0};
  const BodyId creeping = add_or_fail(world, slow);
  BodyDef fast = circle_def({0.0, 20.0}, 0.5);
  fast.velocity = {1.5 * v, 0.0};
  const BodyId moving = add_or_fail(world, fast);
  const int steps_to_sleep = static_cast<int>(std::lround(settings.sleep_time / kDt));
  ASSERT_EQ(steps_to_sleep, 30);
  for (int step = 1; step <= steps_to_sleep; ++step) world.step(kDt);
  EXPECT_TRUE(world.body(resting)->awake) << "asleep before sleep_time";
  EXPECT_TRUE(world.body(creeping)->awake) << "asleep before sleep_time";
  world.step(kDt);
  world.step(kDt);
  EXPECT_FALSE(world.body(resting)->awake) << "awake after sleep_time";
  EXPECT_FALSE(world.body(creeping)->awake) << "awake after sleep_time";
  int moving_asleep = 0;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    moving_asleep += world.body(moving)->awake ? 0 : 1;
  }
  EXPECT_EQ(moving_asleep, 0) << "steps the body faster than sleep_speed was asleep";
  EXPECT_NEAR(world.body(moving)->velocity.x, 1.5 * v, 1e-12);
}

}  // namespace
}  // namespace phys::testing
