// Seams: a floor of static unit boxes exactly side by side.
// Bounds:
//   a box sliding across it never catches on a seam: on every step its horizontal
//   velocity equals its friction decay v0*exp(-k t) to 1e-12 relative (a catch
//   would change it by a large fraction), and it never moves up by more than the
//   slop;
//   a box landing exactly on the seam between two boxes ends resting on top
//   (within the slop), never moved sideways (x exactly unchanged) nor thrown up.
// Measured: the boxes' velocities within 6e-16 of v0 of the decay, the circle's
// within 2.6e-14. How the bounds were validated (the world has no setting for
// either rule, so each was switched off by hand in the core, not committed):
//   a circle beside a tile's corner is no near miss (step_position.cpp): without
//   that rule the circle slider's velocity leaves the decay by 3.6e-3 of v0 at once
//   and its test fails;
//   a box pair is resolved on an axis only if it is the shallower one: without that
//   rule every case here still passes (the Y phase has lifted a landing or sliding
//   box out of its tiles before the X phase looks, and a pair touching on the other
//   axis only is skipped first), so these tests do not guard it.
#include <gtest/gtest.h>

#include <cmath>

#include "stability_scenes.h"

namespace phys::testing {
namespace {

constexpr double kEps = 1.0e-12;

struct Slide {
  Shape shape;
  double half;      // half size of the slider
  double v0;        // initial horizontal speed
  double friction;  // horizontal friction rate
};

class SlidingOverSeams : public ::testing::TestWithParam<Slide> {};

TEST_P(SlidingOverSeams, NeverCatches) {
  const Slide p = GetParam();
  World world;
  add_tiled_floor(world, {0.0, 0.0}, 160);  // 158 m ahead of the slider
  BodyDef def = p.shape == Shape::Box ? box_def({0.0, p.half}, {p.half, p.half})
                                      : circle_def({0.0, p.half}, p.half);
  def.velocity = {p.v0, 0.0};
  def.friction = {p.friction, 0.0};
  const BodyId slider = add_or_fail(world, def);
  const double slop = world.settings().slop;
  for (int step = 1; step <= 240; ++step) {
    world.step(kDt);
    const BodyState s = *world.body(slider);
    const double expected_v = p.v0 * std::exp(-p.friction * step * kDt);
    ASSERT_NEAR(s.velocity.x, expected_v, 1.0e-12 * p.v0) << "caught at step " << step;
    ASSERT_LE(s.position.y, p.half + slop + kEps) << "moved up at step " << step;
    ASSERT_GE(s.position.y, p.half - slop - kEps) << "sank at step " << step;
  }
  // Seams lie at whole x; the slider started at x = 0.
  EXPECT_GE(std::floor(world.body(slider)->position.x), 5.0)
      << "the test must cross seams to mean anything";
}

INSTANTIATE_TEST_SUITE_P(Sliders, SlidingOverSeams,
                         ::testing::Values(Slide{Shape::Box, 0.5, 8.0, 0.5},
                                           Slide{Shape::Box, 0.3, 8.0, 0.5},
                                           Slide{Shape::Box, 0.5, 30.0, 0.0},
                                           Slide{Shape::Circle, 0.5, 8.0, 0.5}));

class LandingOnASeam : public ::testing::TestWithParam<double> {};

TEST_P(LandingOnASeam, SettlesWithoutBeingThrown) {
  // Tiles span [-2, -1], [-1, 0], [0, 1], ...: seams at whole x. The box (half
  // size GetParam()) is centred on the seam at x = 0 and dropped from 2 m.
  const double half = GetParam();
  World world;
  add_tiled_floor(world, {0.0, 0.0}, 6);
  const double start_y = 2.0 + half;
  const BodyId box = add_or_fail(world, box_def({0.0, start_y}, {half, half}));
  const double slop = world.settings().slop;
  for (int step = 1; step <= 180; ++step) {
    world.step(kDt);
    const BodyState s = *world.body(box);
    ASSERT_EQ(s.position.x, 0.0) << "moved sideways at step " << step;
    ASSERT_EQ(s.velocity.x, 0.0) << "thrown sideways at step " << step;
    ASSERT_LE(s.position.y, start_y) << "thrown up at step " << step;
  }
  const BodyState s = *world.body(box);
  EXPECT_NEAR(s.position.y - half, 0.0, slop + kEps);
  EXPECT_EQ(s.velocity.y, 0.0);
}

TEST_P(LandingOnASeam, BoxWithItsEdgeOnTheSeamSettlesOnItsTile) {
  // The box's left edge exactly on the seam x = 0: it rests on the tile [0, 1].
  const double half = GetParam();
  World world;
  add_tiled_floor(world, {0.0, 0.0}, 6);
  const double start_y = 2.0 + half;
  const BodyId box = add_or_fail(world, box_def({half, start_y}, {half, half}));
  for (int step = 1; step <= 180; ++step) {
    world.step(kDt);
    ASSERT_EQ(world.body(box)->position.x, half) << "moved sideways at step " << step;
  }
  EXPECT_NEAR(world.body(box)->position.y - half, 0.0, world.settings().slop + kEps);
}

INSTANTIATE_TEST_SUITE_P(BoxSizes, LandingOnASeam, ::testing::Values(0.5, 0.25, 1.5));

}  // namespace
}  // namespace phys::testing
