// The grid of fixed bodies, the path pairs take in a world with more than a handful
// of them: a kinematic platform that moves across many cells is still found by the
// bodies in its way (its grid is rebuilt as it moves, with nothing asleep to wake),
// and a static body whose filter excludes a falling body lets it through.
#include <gtest/gtest.h>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

// Twelve static floor tiles 4 m wide, their tops at y = 0: more fixed bodies than
// the handful the step tests one by one, so pairs with them come from the grid.
void add_tiled_floor(World& world) {
  for (int i = 0; i < 12; ++i) {
    add_or_fail(world, box_def({-22.0 + 4.0 * i, -0.5}, {2.0, 0.5}, Motion::Static));
  }
}

TEST(FixedGrid, AKinematicPlatformCrossingManyCellsPushesTheBoxInItsWay) {
  WorldSettings settings;
  settings.sleeping = false;  // nothing asleep: no wake rebuilds the lists
  World world(settings);
  add_tiled_floor(world);
  // A kinematic block 1 m wide, its bottom 0.1 m above the floor, from x = -10 at
  // 3 m/s toward a box resting at x = 5: it reaches the box after about 4.8 s.
  BodyDef block = box_def({-10.0, 0.6}, {0.5, 0.5}, Motion::Kinematic);
  block.velocity = {3.0, 0.0};
  const BodyId platform = add_or_fail(world, block);
  const BodyId box = add_or_fail(world, box_def({5.0, 0.25}, {0.25, 0.25}));
  double deepest = 0.0;
  for (int n = 0; n < 8 * 60; ++n) {
    world.step(kDt);
    const BodyState p = *world.body(platform);
    const BodyState b = *world.body(box);
    deepest = std::max(deepest, overlap_depth(p, b));
    // Never behind the block once it has come: it is pushed ahead of it.
    ASSERT_GT(b.position.x - p.position.x, 0.0) << "step " << n;
  }
  const BodyState p = *world.body(platform);
  const BodyState b = *world.body(box);
  // After 8 s the block is at x = 14 and the box in front of it, moving with it.
  EXPECT_NEAR(p.position.x, 14.0, 1e-9);
  EXPECT_NEAR(b.position.x - p.position.x, 0.75, 0.01);
  EXPECT_NEAR(b.velocity.x, 3.0, 0.01);
  // Pushed by one sub-step's motion at most (3 m/s / 60 Hz = 0.05 m).
  EXPECT_LT(deepest, 0.051);
}

TEST(FixedGrid, AStaticBodyWhoseFilterExcludesAFallingBodyLetsItThrough) {
  World world{WorldSettings{}};
  add_tiled_floor(world);
  // Two ledges at y = 2, each in category 1 and blind to category 2.
  Filter ledge_filter;
  ledge_filter.mask_bits = ~0x2u;
  for (const double x : {-5.0, 5.0}) {
    BodyDef ledge = box_def({x, 2.0}, {1.0, 0.1}, Motion::Static);
    ledge.filter = ledge_filter;
    add_or_fail(world, ledge);
  }
  // A box of category 2 falls onto the first ledge, one of category 1 onto the second.
  BodyDef ghost_def = box_def({-5.0, 4.0}, {0.25, 0.25});
  ghost_def.filter.category_bits = 0x2;
  const BodyId ghost = add_or_fail(world, ghost_def);
  const BodyId solid = add_or_fail(world, box_def({5.0, 4.0}, {0.25, 0.25}));
  for (int n = 0; n < 180; ++n) world.step(kDt);
  // The first passed through its ledge and rests on the floor; the second on its ledge.
  EXPECT_NEAR(world.body(ghost)->position.y, 0.25, 0.001);
  EXPECT_NEAR(world.body(solid)->position.y, 2.1 + 0.25, 0.001);
}

}  // namespace
}  // namespace phys::testing
