// Static friction in the position passes undoes a body's creep, never its escape from
// a squeeze (docs/PHYSICS.md, "Squeezes at high friction").
//
// A ball put 0.05 m deep into a static wall and a static ball below and beside it can
// get out of both only by rising between them. Before the rule, the wall's static
// friction undid that rise in every position pass, and after 1 s the deepest overlap
// was still 0.099, 0.094 and 0.082 m in the three cases below, for ever: every wedge
// within the friction cone jammed. A world without gravity jammed the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// Sleeping off: a jammed ball must not pass for settled because it fell asleep.
WorldSettings awake_settings() {
  WorldSettings settings;
  settings.sleeping = false;
  return settings;
}

struct Squeeze {
  double mu;
  double degrees;  // how far below level the static ball's contact lies
  bool gravity;
};

class SqueezedBall : public ::testing::TestWithParam<Squeeze> {};

// Bound: after 1 s no overlap beyond twice the slop, and the ball has risen out of
// the wedge by more than 0.05 m. Measured: overlap 0, risen by 0.10 to 0.30 m.
TEST_P(SqueezedBall, RisesOutOfTheSqueeze) {
  const Squeeze squeeze = GetParam();
  WorldSettings settings = awake_settings();
  if (!squeeze.gravity) settings.gravity = {0.0, 0.0};
  World world(settings);
  BodyDef wall = box_def({-0.5, 0.0}, {0.5, 10.0}, Motion::Static);
  wall.contact_friction = squeeze.mu;
  add_or_fail(world, wall);
  const double depth = 0.05;
  const Vec2 start{0.5 - depth, 2.0};  // into the wall by depth
  const double angle = radians(squeeze.degrees);
  const double apart = 1.0 - depth;  // and into the static ball by about as much
  BodyDef below = circle_def({start.x + apart * std::cos(angle), start.y - apart * std::sin(angle)},
                             0.5, Motion::Static);
  below.contact_friction = squeeze.mu;
  add_or_fail(world, below);
  BodyDef ball_def = circle_def(start, 0.5);
  ball_def.contact_friction = squeeze.mu;
  const BodyId ball = add_or_fail(world, ball_def);
  ASSERT_GT(max_overlap(world.bodies()), 0.04);

  for (int step = 0; step < 60; ++step) world.step(kDt);

  const double overlap = max_overlap(world.bodies());
  const double risen = world.body(ball)->position.y - start.y;
  std::printf("mu %.1f, %.0f degrees: overlap %.3g m, risen %.3f m\n", squeeze.mu, squeeze.degrees,
              overlap, risen);
  EXPECT_LE(overlap, 2.0 * settings.slop);
  EXPECT_GT(risen, 0.05);
  EXPECT_TRUE(is_finite(world.body(ball)->velocity));
}

INSTANTIATE_TEST_SUITE_P(Wedges, SqueezedBall,
                         ::testing::Values(Squeeze{0.5, 10.0, true}, Squeeze{1.0, 30.0, true},
                                           Squeeze{5.0, 50.0, true}, Squeeze{1.0, 30.0, false},
                                           Squeeze{5.0, 50.0, false}),
                         [](const auto& param_info) {
                           const Squeeze& s = param_info.param;
                           return "mu" + std::to_string(static_cast<int>(s.mu * 10.0)) + "_deg" +
                                  std::to_string(static_cast<int>(s.degrees)) +
                                  (s.gravity ? "" : "_no_gravity");
                         });

// Without gravity, the creep that static friction undoes comes from a body's own
// acceleration: a ball pushed at 10 m/s^2 into a static ball, the contact `degrees`
// off the line of the push, holds if tan(degrees) <= mu and slides otherwise
// (mu = 0.5: 26.57 degrees). Held: within 2e-5 m of where it was put after 10 s.
// Sliding: more than 0.05 m.
struct Push {
  double degrees;
  bool holds;
};

class PushedBall : public ::testing::TestWithParam<Push> {};

TEST_P(PushedBall, HoldsInsideTheConeWithoutGravity) {
  const Push push = GetParam();
  WorldSettings settings = awake_settings();
  settings.gravity = {0.0, 0.0};
  World world(settings);
  BodyDef base = circle_def({0.0, 0.0}, 0.5, Motion::Static);
  base.contact_friction = 0.5;
  add_or_fail(world, base);
  const double angle = radians(push.degrees);
  const Vec2 start{std::cos(angle), std::sin(angle)};
  BodyDef ball_def = circle_def(start, 0.5);
  ball_def.contact_friction = 0.5;
  ball_def.acceleration = {-10.0, 0.0};
  const BodyId ball = add_or_fail(world, ball_def);
  for (int step = 0; step < 600; ++step) world.step(kDt);
  const double moved = length(world.body(ball)->position - start);
  if (push.holds) {
    EXPECT_LT(moved, 2e-5);
    EXPECT_GT(world.counters().friction_holds, 0u);
  } else {
    EXPECT_GT(moved, 0.05);
  }
}

INSTANTIATE_TEST_SUITE_P(Cone, PushedBall,
                         ::testing::Values(Push{5.0, true}, Push{20.0, true}, Push{26.0, true},
                                           Push{27.0, false}),
                         [](const auto& param_info) {
                           const Push& p = param_info.param;
                           return "deg" + std::to_string(static_cast<int>(p.degrees)) +
                                  (p.holds ? "_holds" : "_slides");
                         });

}  // namespace
}  // namespace phys::testing
