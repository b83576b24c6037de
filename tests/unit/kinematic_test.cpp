// Kinematic bodies (Motion::Kinematic): a platform led along a path by its velocity
// goes exactly where the sums of velocity * sub-step put it, whatever it meets;
// carries a box standing on it, sideways and up; pushes a box in its way; wakes a
// box asleep on it when it starts; and meets neither static nor kinematic bodies.
#include <gtest/gtest.h>

#include <cmath>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

class Kinematic : public WorldTest {
 protected:
  BodyId make_platform(Vec2 at, Vec2 half, Vec2 velocity = {}) {
    BodyDef def = box_def(at, half, Motion::Kinematic);
    def.velocity = velocity;
    def.contact_friction = 0.8;
    return add(def);
  }
  BodyId make_rider(Vec2 at) {
    BodyDef def = box_def(at, {0.25, 0.25});
    def.contact_friction = 0.8;
    return add(def);
  }
  // Where a kinematic body at x moving at v is after one step: the core adds
  // v * h once per sub-step.
  double advance(double x, double v) const {
    const double h = kDt / world_.settings().substeps;
    for (int i = 0; i < world_.settings().substeps; ++i) x += v * h;
    return x;
  }
};

// The path: x velocity 1.5 sin(t) (peak acceleration 1.5 m/s^2, under the 7.8 m/s^2
// friction can give a 0.8 box on a 0.8 platform).
double path_velocity(int step) { return 1.5 * std::sin(step * kDt); }

TEST_F(Kinematic, APlatformOnAPathCarriesABoxStandingOnIt) {
  const BodyId platform = make_platform({0.0, 0.0}, {2.0, 0.25});
  const BodyId box = make_rider({0.5, 0.5});
  step_n(60);  // the box settles
  ASSERT_NEAR(position(box).y, 0.5, 0.001);
  const double offset = position(box).x - position(platform).x;
  double expected_x = position(platform).x;
  double worst = 0.0;
  for (int n = 0; n < 600; ++n) {
    const double v = path_velocity(n);
    ASSERT_TRUE(world_.set_velocity(platform, {v, 0.0}));
    world_.step(kDt);
    expected_x = advance(expected_x, v);
    // The platform goes where its velocity takes it, to the rounding: nothing pushes it.
    ASSERT_EQ(position(platform).x, expected_x) << "step " << n;
    ASSERT_EQ(position(platform).y, 0.0);
    // The box moves by the velocity its contact gave it in the step before (the
    // moves come before the velocity solver), so it trails the platform by the
    // platform's velocity times one step, and by no more: it does not slip.
    const double trailing = position(box).x - position(platform).x - offset;
    worst = std::max(worst, std::fabs(trailing + v * kDt));
  }
  // Within 0.5 mm of one step behind over 10 s of swaying (the step is up to 25 mm;
  // without friction the box would stay put while the platform moved 1.5 m under it).
  EXPECT_LT(worst, 0.0005);
  EXPECT_NEAR(position(box).y, 0.5, 0.001);
}

TEST_F(Kinematic, ARisingPlatformLiftsTheBoxOnIt) {
  const BodyId platform = make_platform({0.0, 0.0}, {2.0, 0.25});
  const BodyId box = make_rider({0.0, 0.5});
  step_n(30);
  ASSERT_TRUE(world_.set_velocity(platform, {0.0, 1.0}));
  for (int n = 0; n < 120; ++n) {
    world_.step(kDt);
    // Resting on it: never more than a few slops above, never sunk into it.
    ASSERT_NEAR(position(box).y - position(platform).y, 0.5, 0.002) << "step " << n;
  }
  EXPECT_NEAR(velocity(box).y, 1.0, 1e-6);
}

TEST_F(Kinematic, APlatformPushesABoxInItsWay) {
  make_floor(0.0);
  // A pusher skimming the floor (kinematic and static bodies do not meet).
  const BodyId pusher = make_platform({-3.0, 0.5}, {0.5, 0.5}, {1.0, 0.0});
  const BodyId box = make_box({0.0, 0.25}, {0.25, 0.25});
  double expected_x = -3.0;
  for (int n = 0; n < 300; ++n) {
    world_.step(kDt);
    expected_x = advance(expected_x, 1.0);
    ASSERT_EQ(position(pusher).x, expected_x);
    // The box is never left inside the pusher by more than the slop.
    ASSERT_GE(position(box).x - 0.25, position(pusher).x + 0.5 - 1e-4) << "step " << n;
  }
  // Pushed along at the pusher's speed, on the floor.
  EXPECT_NEAR(velocity(box).x, 1.0, 1e-6);
  EXPECT_NEAR(position(box).y, 0.25, 0.001);
  EXPECT_GT(position(box).x, 1.5);
}

TEST_F(Kinematic, MeetsNeitherStaticNorKinematicBodiesAndFeelsNoGravity) {
  make_static_box({0.0, 0.0}, {0.5, 2.0});
  const BodyId a = make_platform({-3.0, 0.0}, {0.5, 0.5}, {1.0, 0.0});
  const BodyId b = make_platform({3.0, 0.0}, {0.5, 0.5}, {-1.0, 0.0});
  double xa = -3.0;
  double xb = 3.0;
  for (int n = 0; n < 360; ++n) {
    world_.step(kDt);
    xa = advance(xa, 1.0);
    xb = advance(xb, -1.0);
    ASSERT_EQ(position(a), (Vec2{xa, 0.0}));
    ASSERT_EQ(position(b), (Vec2{xb, 0.0}));
  }
  EXPECT_EQ(state(a).mass, 0.0);
  EXPECT_EQ(state(a).motion, Motion::Kinematic);
  EXPECT_FALSE(world_.set_acceleration(a, {1.0, 0.0}));
}

TEST_F(Kinematic, ABoxAsleepOnAStillPlatformWakesWhenItMoves) {
  const BodyId platform = make_platform({0.0, 0.0}, {2.0, 0.25});
  const BodyId box = make_rider({0.0, 0.5});
  step_n(240);
  ASSERT_FALSE(state(box).awake);
  ASSERT_TRUE(world_.set_velocity(platform, {0.0, 0.5}));
  step_n(60);
  EXPECT_TRUE(state(box).awake);
  EXPECT_NEAR(position(box).y - position(platform).y, 0.5, 0.002);
}

}  // namespace
}  // namespace phys::testing
