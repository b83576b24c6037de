// Hard case 9, extreme numbers. The limits (WorldSettings defaults): speeds are
// clamped to max_speed = 1000 m/s, accelerations to max_acceleration = 1e5 m/s^2.
// Bounds: with accelerations of 1e30, velocities far beyond the limit, and masses
// of 1e-6 against 1e6, every number in the world stays finite, every speed stays
// at most max_speed, and the contacts still hold (overlap at most the slop).
#include <gtest/gtest.h>

#include <limits>

#include "stability_scenes.h"

namespace phys::testing {
namespace {

constexpr double kEps = 1.0e-9;

class ExtremeNumbers : public WorldTest {
 protected:
  void expect_sane(const char* when) {
    const std::vector<BodyState> bodies = world_.bodies();
    ASSERT_TRUE(all_finite(bodies)) << when;
    for (const BodyState& b : bodies) {
      EXPECT_LE(length(b.velocity), world_.settings().max_speed * (1.0 + kEps)) << when;
      EXPECT_LE(length(b.acceleration), world_.settings().max_acceleration * (1.0 + kEps)) << when;
    }
  }
};

TEST_F(ExtremeNumbers, AccelerationOf1e30IsClampedAndTheWorldStaysFinite) {
  make_floor(0.0);
  const BodyId pushed = make_box({0.0, 0.5});
  ASSERT_TRUE(world_.set_acceleration(pushed, {1.0e30, 1.0e30}));
  for (int step = 0; step < 600; ++step) {
    world_.step(kDt);
    ASSERT_NO_FATAL_FAILURE(expect_sane("after a push of 1e30"));
  }
  EXPECT_EQ(length(velocity(pushed)) > 0.0, true);
}

TEST_F(ExtremeNumbers, AccelerationOf1e30InTheDefinitionIsClampedToo) {
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5});
  def.acceleration = {-1.0e30, 1.0e30};
  add(def);
  for (int step = 0; step < 120; ++step) world_.step(kDt);
  expect_sane("after a defined acceleration of 1e30");
}

TEST_F(ExtremeNumbers, VelocityBeyondTheLimitIsClampedOnTheNextStep) {
  const BodyId fast = make_circle({0.0, 0.0});
  ASSERT_TRUE(world_.set_velocity(fast, {3.0e6, -4.0e6}));
  world_.step(kDt);
  EXPECT_NEAR(length(velocity(fast)), world_.settings().max_speed,
              world_.settings().max_speed * kEps);
  EXPECT_GT(world_.counters().speed_clamps, 0u);
  expect_sane("after a kick of 5e6 m/s");
}

TEST_F(ExtremeNumbers, HugeVelocityInTheDefinitionStaysFiniteAgainstWalls) {
  make_floor(0.0);
  make_static_box({-20.5, 10.0}, {0.5, 10.0});
  make_static_box({20.5, 10.0}, {0.5, 10.0});
  BodyDef def = circle_def({0.0, 5.0}, 0.5);
  def.velocity = {1.0e300, -1.0e300};
  def.restitution = 1.0;
  const BodyId ball = add(def);
  for (int step = 0; step < 600; ++step) {
    world_.step(kDt);
    ASSERT_NO_FATAL_FAILURE(expect_sane("after a velocity of 1e300"));
    const Vec2 p = position(ball);
    ASSERT_GT(p.x, -20.0) << "through the left wall at step " << step;
    ASSERT_LT(p.x, 20.0) << "through the right wall at step " << step;
    ASSERT_GT(p.y, 0.0) << "through the floor at step " << step;
  }
}

TEST_F(ExtremeNumbers, HeavyBoxOnALightBoxOnTheFloor) {
  // 1e6 kg resting on 1e-6 kg: the light box must not be pressed into the floor.
  make_floor(0.0);
  const BodyId light = make_box({0.0, 0.5}, {0.5, 0.5}, 1.0e-6);
  const BodyId heavy = make_box({0.0, 2.0}, {0.5, 0.5}, 1.0e6);
  for (int step = 0; step < 600; ++step) {
    world_.step(kDt);
    ASSERT_NO_FATAL_FAILURE(expect_sane("heavy on light"));
  }
  const double slop = world_.settings().slop;
  EXPECT_NEAR(position(light).y, 0.5, 2.0 * slop);
  EXPECT_NEAR(position(heavy).y, 1.5, 3.0 * slop);
  EXPECT_LE(max_overlap(world_.bodies()), slop);
}

TEST_F(ExtremeNumbers, LightBodyHittingAHeavyOneConservesMomentum) {
  // Sleeping off: the heavy body's share, 2e-11 m/s, is far below sleep_speed, and
  // a sleeping body's velocity is zeroed by design; this test is about the ratio.
  WorldSettings settings = zero_gravity();
  settings.sleeping = false;
  reset(settings);
  BodyDef light = circle_def({0.0, 0.0}, 0.5);
  light.mass = 1.0e-6;
  // 10 m/s: slow enough (1/6 m a step) that this is about the mass ratio, not about
  // tunnelling, which the core sweeps only against static bodies.
  light.velocity = {10.0, 0.0};
  light.restitution = 1.0;
  BodyDef heavy = circle_def({20.0, 0.0}, 0.5);
  heavy.mass = 1.0e6;
  heavy.restitution = 1.0;
  const BodyId a = add(light);
  const BodyId b = add(heavy);
  for (int step = 0; step < 120; ++step) world_.step(kDt);
  expect_sane("light against heavy");
  const double p = 1.0e-6 * velocity(a).x + 1.0e6 * velocity(b).x;
  EXPECT_NEAR(p, 1.0e-6 * 10.0, 1.0e-6 * 10.0 * 1.0e-9);
  // Elastic: v1' = (m1 - m2)/(m1 + m2) v = -10 (1 - 2e-12), v2' = 2 m1/(m1 + m2) v = 2e-11.
  EXPECT_NEAR(velocity(a).x, -10.0, 1.0e-9);
  EXPECT_NEAR(velocity(b).x, 2.0e-11, 1.0e-15);
}

TEST_F(ExtremeNumbers, BodiesFarOutStayFinite) {
  // 1e12 m from the origin (a double still resolves 0.1 mm there).
  reset(WorldSettings{});
  add(box_def({1.0e12, 1.0e12 - 0.5}, {5.0, 0.5}, Motion::Static));
  const BodyId box = make_box({1.0e12, 1.0e12 + 3.0});
  for (int step = 0; step < 240; ++step) world_.step(kDt);
  expect_sane("1e12 m out");
  EXPECT_NEAR(position(box).y, 1.0e12 + 0.5, 1.0e-3);
}

}  // namespace
}  // namespace phys::testing
