// Extreme numbers. The limits (WorldSettings defaults): speeds are
// clamped to max_speed = 1000 m/s, accelerations to max_acceleration = 1e5 m/s^2.
// Bounds: with accelerations of 1e30, velocities far beyond the limit, and masses
// of 1e-6 against 1e6, every number in the world stays finite, every speed and
// acceleration stays at most its limit (to 4 ulps), a clamped value has the
// limit's length (DOUBLE_EQ) in the direction it was given, and the contacts still
// hold (overlap at most the slop).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "stability_scenes.h"

namespace phys::testing {
namespace {

// A clamped length is the limit to within an ulp or two (clamp_length, vec2.h, and
// the step's own speed cap).
constexpr double kUlps = 4.0 * std::numeric_limits<double>::epsilon();

class ExtremeNumbers : public WorldTest {
 protected:
  void expect_sane(const char* when) {
    const std::vector<BodyState> bodies = world_.bodies();
    ASSERT_TRUE(all_finite(bodies)) << when;
    for (const BodyState& b : bodies) {
      EXPECT_LE(length(b.velocity), world_.settings().max_speed * (1.0 + kUlps)) << when;
      EXPECT_LE(length(b.acceleration), world_.settings().max_acceleration * (1.0 + kUlps)) << when;
    }
  }
};

TEST_F(ExtremeNumbers, AccelerationOf1e30IsClampedAndTheWorldStaysFinite) {
  make_floor(0.0);
  const BodyId pushed = make_box({0.0, 0.5});
  ASSERT_TRUE(world_.set_acceleration(pushed, {1.0e30, 1.0e30}));
  // Clamped at once, along the diagonal it was given: 1e5 / sqrt 2 on each axis.
  const Vec2 a = state(pushed).acceleration;
  EXPECT_DOUBLE_EQ(a.x, world_.settings().max_acceleration / std::sqrt(2.0));
  EXPECT_EQ(a.y, a.x);
  for (int step = 0; step < 600; ++step) {
    world_.step(kDt);
    ASSERT_NO_FATAL_FAILURE(expect_sane("after a push of 1e30"));
    // 1178 m/s gained a step (less 0.16 m/s of gravity) is over the limit from the
    // first step on: the box leaves the floor up and to the right at max_speed.
    const Vec2 v = velocity(pushed);
    ASSERT_DOUBLE_EQ(length(v), world_.settings().max_speed) << "at step " << step;
    ASSERT_GT(v.x, 0.0);
    ASSERT_GT(v.y, 0.0);
    ASSERT_EQ(state(pushed).acceleration, a);
  }
}

TEST_F(ExtremeNumbers, AccelerationOf1e30InTheDefinitionIsClampedToo) {
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5});
  def.acceleration = {-1.0e30, 1.0e30};
  const BodyId box = add(def);
  const Vec2 a = state(box).acceleration;
  EXPECT_DOUBLE_EQ(a.y, world_.settings().max_acceleration / std::sqrt(2.0));
  EXPECT_EQ(a.x, -a.y);
  EXPECT_EQ(world_.counters().acceleration_clamps, 1u);
  for (int step = 0; step < 120; ++step) {
    world_.step(kDt);
    ASSERT_NO_FATAL_FAILURE(expect_sane("after a defined acceleration of 1e30"));
    // Free flight: over max_speed from the first step on (1178 m/s a step).
    ASSERT_DOUBLE_EQ(length(velocity(box)), world_.settings().max_speed) << "at step " << step;
  }
}

TEST_F(ExtremeNumbers, VelocityBeyondTheLimitIsClampedAtOnceAndOnTheNextStep) {
  const BodyId fast = make_circle({0.0, 0.0});
  ASSERT_TRUE(world_.set_velocity(fast, {3.0e6, -4.0e6}));
  // The 3-4-5 direction scaled to 1000 m/s is exactly (600, -800).
  EXPECT_EQ(velocity(fast), (Vec2{600.0, -800.0}));
  EXPECT_EQ(world_.counters().speed_clamps, 1u);
  world_.step(kDt);
  // Gravity takes it over the limit again; the step caps it back.
  EXPECT_DOUBLE_EQ(length(velocity(fast)), world_.settings().max_speed);
  EXPECT_EQ(world_.counters().speed_clamps, 2u);
  expect_sane("after a kick of 5e6 m/s");
}

TEST_F(ExtremeNumbers, HugeVelocityInTheDefinitionBouncesAtMaxSpeedInsideTheWalls) {
  // A closed room 39 m by 19 m inside (ball centres in x in [-19.5, 19.5] and y in
  // [0.5, 19.5]), elastic ball, no friction: the ball keeps its sideways speed,
  // crossing the room 181 times in 10 s.
  make_floor(0.0);
  make_static_box({-20.5, 10.0}, {0.5, 10.0});
  make_static_box({20.5, 10.0}, {0.5, 10.0});
  make_static_box({0.0, 20.5}, {21.0, 0.5});
  BodyDef def = circle_def({0.0, 5.0}, 0.5);
  def.velocity = {1.0e300, -1.0e300};
  def.restitution = 1.0;
  const BodyId ball = add(def);
  const double max_speed = world_.settings().max_speed;
  const double slop = world_.settings().slop;
  // Clamped at once, along the diagonal it was given.
  const double diagonal = max_speed / std::sqrt(2.0);
  EXPECT_DOUBLE_EQ(velocity(ball).x, diagonal);
  EXPECT_EQ(velocity(ball).y, -velocity(ball).x);

  // The first step: gravity takes the speed over the limit, and the step caps the
  // velocity and the move alike, so the ball moves v_x dt sideways, with
  // v_x = diagonal * max_speed / |(diagonal, -diagonal - g dt)|; the floor it
  // meets on the way turns only v_y.
  world_.step(kDt);
  const double vx1 =
      diagonal * max_speed / std::hypot(diagonal, diagonal - world_.settings().gravity.y * kDt);
  EXPECT_DOUBLE_EQ(velocity(ball).x, vx1);
  EXPECT_NEAR(position(ball).x, vx1 * kDt, 1.0e-9);

  double sideways = std::abs(position(ball).x);
  int left_hits = 0;
  int right_hits = 0;
  double previous_vx = velocity(ball).x;
  for (int step = 1; step < 600; ++step) {
    world_.step(kDt);
    ASSERT_NO_FATAL_FAILURE(expect_sane("after a velocity of 1e300"));
    const Vec2 p = position(ball);
    const Vec2 v = velocity(ball);
    ASSERT_LE(max_overlap(world_.bodies()), slop) << "at step " << step;
    ASSERT_GE(p.x, -19.5 - slop) << "through the left wall at step " << step;
    ASSERT_LE(p.x, 19.5 + slop) << "through the right wall at step " << step;
    ASSERT_GE(p.y, 0.5 - slop) << "through the floor at step " << step;
    ASSERT_LE(p.y, 19.5 + slop) << "through the ceiling at step " << step;
    // Sideways speed kept to 0.1%: the walls return it whole, and only the cap of
    // the speed (gravity keeps adding to it) takes a little off (measured 0.03%).
    ASSERT_NEAR(std::abs(v.x), diagonal, 1.0e-3 * diagonal) << "at step " << step;
    ASSERT_NEAR(length(v), max_speed, 1.0e-3 * max_speed) << "at step " << step;
    if (v.x < 0.0 && previous_vx > 0.0) ++right_hits;
    if (v.x > 0.0 && previous_vx < 0.0) ++left_hits;
    previous_vx = v.x;
    sideways += std::abs(v.x) * kDt;
  }
  // One wall hit per 39 m travelled sideways (the first after 19.5 m).
  const double expected_hits = (sideways + 19.5) / 39.0;
  EXPECT_NEAR(left_hits + right_hits, expected_hits, 1.0);
  EXPECT_NEAR(left_hits, right_hits, 1.0);
  std::printf("huge velocity: %d + %d wall hits over %.1f m sideways (%.1f expected)\n", left_hits,
              right_hits, sideways, expected_hits);
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
  // At the largest |coordinate| the core takes, 1e7 m from the origin (a double still
  // resolves 2e-9 m there); beyond it, 1e12 m out, a body is refused.
  reset(WorldSettings{});
  constexpr double kFar = 1.0e7;
  add(box_def({kFar - 10.0, kFar - 10.5}, {5.0, 0.5}, Motion::Static));
  const BodyId box = make_box({kFar - 10.0, kFar - 7.0});
  for (int step = 0; step < 240; ++step) world_.step(kDt);
  expect_sane("1e7 m out");
  EXPECT_NEAR(position(box).y, kFar - 9.5, 1.0e-3);
  BodyDefError error = BodyDefError::None;
  EXPECT_FALSE(world_.add_body(box_def({1.0e12, 1.0e12}, {0.5, 0.5}), &error).is_valid());
  EXPECT_EQ(error, BodyDefError::OutOfBounds);
}

}  // namespace
}  // namespace phys::testing
