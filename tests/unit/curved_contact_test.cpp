// Contacts on curved static surfaces (a static circle, a box's corner), and static
// friction on a slope.
//
// The per-axis move stops at the time of impact with a static body and leaves the
// pressed velocity for the restitution phase to remove. On a curve the move on the
// other axis can leave the two shapes a hair apart; before contacts were recorded
// where the sweep stopped, that contact was missed: the ball hung on the curve while
// its downward speed grew by g*dt every step (-9.7 m/s after 1 s, 0.01 m below its
// start). These tests fail that way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

constexpr double kGravity = 9.81;
constexpr double kRadius = 0.5;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

enum class Support { Circle, BoxCorner };

// A ball of radius 0.5 at rest on top of a static support, its contact normal
// `degrees` from vertical. Returns the world and the ball's id.
struct Perch {
  World world;
  BodyId ball;
  Vec2 start;
};

void perch(Perch& out, Support support, double degrees, double mu) {
  BodyDef base = support == Support::Circle ? circle_def({0.0, 0.0}, kRadius, Motion::Static)
                                            : box_def({0.0, 0.0}, {0.5, 0.5}, Motion::Static);
  base.contact_friction = mu;
  add_or_fail(out.world, base);
  // The point the ball rests on, and the distance from it to the ball's centre.
  const Vec2 pivot = support == Support::Circle ? Vec2{0.0, 0.0} : Vec2{0.5, 0.5};
  const double reach = support == Support::Circle ? 2.0 * kRadius : kRadius;
  const double angle = radians(degrees);
  BodyDef ball =
      circle_def(pivot + Vec2{reach * std::sin(angle), reach * std::cos(angle)}, kRadius);
  ball.contact_friction = mu;
  out.start = ball.position;
  out.ball = add_or_fail(out.world, ball);
}

WorldSettings awake_settings() {
  WorldSettings settings;
  settings.sleeping = false;
  return settings;
}

class SlidingOffACurve : public ::testing::TestWithParam<Support> {};

// Frictionless, released 20 degrees from the top: the ball slides off and falls.
// Bounds: after 1 s it is below the support's top (it left the curve; it stays on it
// for about 0.4 s), and at no step does its kinetic energy exceed the potential
// energy it lost by more than m*g*0.03 m. Measured: 0.025 m (circle) and 0.018 m
// (corner), constant once it has left the curve: the position lags the velocity by
// part of a step while the ball is on the curve. A ball hanging on the curve gains
// about 4.7 m of height's worth in the first second: validated with the contact
// at the sweep's stop switched off by hand (the world has no setting for it), the
// excess was 4.01 m (circle) and 4.74 m (corner), the ball still 0.81 and 0.96 m
// up after 1 s, and every bound of this test failed.
TEST_P(SlidingOffACurve, BallSlidesOffWithoutGainingEnergy) {
  Perch p{World(awake_settings()), {}, {}};
  perch(p, GetParam(), 20.0, 0.0);
  double worst_excess = -1.0;
  for (int step = 0; step < 60; ++step) {
    p.world.step(kDt);
    const BodyState ball = *p.world.body(p.ball);
    const double kinetic = 0.5 * dot(ball.velocity, ball.velocity);  // per unit mass
    const double lost = kGravity * (p.start.y - ball.position.y);
    worst_excess = std::max(worst_excess, (kinetic - lost) / kGravity);
  }
  const BodyState ball = *p.world.body(p.ball);
  EXPECT_LT(ball.position.y, 0.5) << "the ball still hangs on the curve";
  EXPECT_GT(ball.velocity.x, 0.5) << "the curve turned none of the fall sideways";
  EXPECT_LT(worst_excess, 0.03) << "metres of height gained";
}

INSTANTIATE_TEST_SUITE_P(Supports, SlidingOffACurve,
                         ::testing::Values(Support::Circle, Support::BoxCorner),
                         [](const auto& param_info) {
                           return param_info.param == Support::Circle ? "static_circle"
                                                                      : "box_corner";
                         });

struct Slope {
  double degrees;
  double mu;
  bool holds;
};

class StaticFriction : public ::testing::TestWithParam<Slope> {};

// Coulomb's cone: a ball resting on a static circle at `degrees` from the top holds
// still if tan(degrees) <= mu, else slides. With mu = 0.5 the cone is 26.57 degrees.
// Held: within 2e-5 m of where it was put after 10 s (the slop pushes it out by
// 1e-5 once). Sliding: more than 0.05 m in 1 s (measured 0.094 and 0.60 m).
// Static friction in the position passes is what holds it; the world has no setting
// for it, so it was validated by switching it off by hand. With held support (the
// default) the ball sinks into the slope only in its first step, static friction
// acts once, and without it the ball slips 1.2e-4, 4.7e-4 and 9.6e-4 m at 5, 20 and
// 45 degrees, but only the slop's 1e-5 m at 26: hence the runs without held support
// too, where the ball sinks every step and, without static friction, creeps down
// the slope (the velocity pass's contact friction slows the creep but cannot undo
// it): 6.5e-4, 2.7e-3, 2.9e-3 and 7.0e-3 m in 10 s at 5, 20, 26 and 45 degrees
// (1.0e-5 m with it, at every angle).
void expect_holds_or_slides(const Slope& slope, bool hold_resting_support) {
  WorldSettings settings = awake_settings();
  settings.hold_resting_support = hold_resting_support;
  Perch p{World(settings), {}, {}};
  perch(p, Support::Circle, slope.degrees, slope.mu);
  const int steps = slope.holds ? 600 : 60;
  for (int step = 0; step < steps; ++step) p.world.step(kDt);
  const BodyState ball = *p.world.body(p.ball);
  const double moved = length(ball.position - p.start);
  if (slope.holds) {
    EXPECT_LT(moved, 2e-5);
    EXPECT_LT(length(ball.velocity), 1e-12);
    EXPECT_GT(p.world.counters().friction_holds, 0u);
  } else {
    EXPECT_GT(moved, 0.05);
  }
}

TEST_P(StaticFriction, HoldsInsideTheConeAndSlidesOutside) {
  expect_holds_or_slides(GetParam(), true);
}

TEST_P(StaticFriction, HoldsInsideTheConeAndSlidesOutsideWithoutHeldSupport) {
  expect_holds_or_slides(GetParam(), false);
}

INSTANTIATE_TEST_SUITE_P(Cone, StaticFriction,
                         ::testing::Values(Slope{5.0, 0.5, true}, Slope{20.0, 0.5, true},
                                           Slope{26.0, 0.5, true}, Slope{27.0, 0.5, false},
                                           Slope{20.0, 0.3, false}, Slope{45.0, 1.2, true}),
                         [](const auto& param_info) {
                           const Slope& s = param_info.param;
                           return "deg" + std::to_string(static_cast<int>(s.degrees)) + "_mu" +
                                  std::to_string(static_cast<int>(s.mu * 100.0)) +
                                  (s.holds ? "_holds" : "_slides");
                         });

}  // namespace
}  // namespace phys::testing
