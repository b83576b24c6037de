// Collisions inside a stepping world: a box lands on the floor and stays there
// without sliding, a box sliding into a wall stops at the wall, a circle lands on
// a box, restitution 0 / 0.5 / 1 set the bounce, and two dynamic bodies of masses
// 1 and 3 split separation and impulse by inverse mass with momentum conserved.
#include <gtest/gtest.h>

#include <cmath>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

class WorldCollision : public WorldTest {
 protected:
  double slop() const { return world_.settings().slop; }
};

// Rounding allowance on top of the slop: positions near 1 m carry ~1e-16 m error.
constexpr double kEps = 1.0e-12;

TEST_F(WorldCollision, BoxLandingOnTheFloorEndsOnTopWithinSlop) {
  make_floor(0.0);
  const BodyId box = make_box({3.3, 3.0});
  step_n(120);  // falls 2.5 m in 0.71 s, then rests
  const BodyState s = state(box);
  const double bottom = s.position.y - 0.5;
  EXPECT_GE(bottom, -slop() - kEps) << "sank into the floor";
  EXPECT_LE(bottom, slop() + kEps) << "floats above the floor";
  EXPECT_EQ(s.velocity.y, 0.0);
}

TEST_F(WorldCollision, BoxLandingOnTheFloorIsNotPushedSideways) {
  make_floor(0.0);
  const BodyId box = make_box({3.3, 3.0});
  for (int step = 0; step < 120; ++step) {
    world_.step(kDt);
    ASSERT_EQ(position(box).x, 3.3) << "step " << step;
    ASSERT_EQ(velocity(box).x, 0.0) << "step " << step;
  }
}

TEST_F(WorldCollision, BoxNeverSinksBelowTheFloorWhileLanding) {
  make_floor(0.0);
  const BodyId box = make_box({0.0, 3.0});
  for (int step = 0; step < 120; ++step) {
    world_.step(kDt);
    ASSERT_GE(position(box).y - 0.5, -slop() - kEps) << "step " << step;
  }
}

TEST_F(WorldCollision, BoxSlidingIntoAWallStopsAtTheWall) {
  make_floor(0.0);
  make_static_box({5.5, 5.0}, {0.5, 5.0});  // left face at x = 5
  BodyDef def = box_def({0.0, 0.5}, {0.5, 0.5});
  def.velocity = {10.0, 0.0};
  const BodyId box = add(def);
  for (int step = 0; step < 60; ++step) {
    world_.step(kDt);
    ASSERT_LE(position(box).x + 0.5, 5.0 + slop() + kEps) << "in the wall at step " << step;
  }
  const BodyState s = state(box);
  EXPECT_GE(s.position.x + 0.5, 5.0 - slop() - kEps) << "stopped short of the wall";
  EXPECT_EQ(s.velocity.x, 0.0);
  EXPECT_LE(s.position.y - 0.5, slop() + kEps) << "climbed the wall";
}

TEST_F(WorldCollision, BoxSlidingSlowlyIntoAWallStopsAtTheWallWithoutSweeping) {
  WorldSettings settings;
  settings.continuous = false;  // 2 m/s moves 3.3 cm a step: plain overlap resolution
  reset(settings);
  make_floor(0.0);
  make_static_box({5.5, 5.0}, {0.5, 5.0});
  BodyDef def = box_def({0.0, 0.5}, {0.5, 0.5});
  def.velocity = {2.0, 0.0};
  const BodyId box = add(def);
  step_n(180);
  const BodyState s = state(box);
  EXPECT_NEAR(s.position.x + 0.5, 5.0, slop() + kEps);
  EXPECT_EQ(s.velocity.x, 0.0);
}

TEST_F(WorldCollision, CircleLandsOnABoxAndRests) {
  make_floor(0.0);
  const BodyId ball = make_circle({1.25, 3.0}, 0.5);
  step_n(120);
  const BodyState s = state(ball);
  EXPECT_NEAR(s.position.y - 0.5, 0.0, slop() + kEps);
  EXPECT_EQ(s.position.x, 1.25);
  EXPECT_EQ(s.velocity.y, 0.0);
}

TEST_F(WorldCollision, CircleHittingABoxSideStops) {
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  reset(settings);
  make_static_box({3.0, 0.0}, {0.5, 2.0});  // left face at x = 2.5
  BodyDef def = circle_def({0.0, 0.0}, 0.5);
  def.velocity = {3.0, 0.0};
  const BodyId ball = add(def);
  step_n(120);
  const BodyState s = state(ball);
  EXPECT_NEAR(s.position.x + 0.5, 2.5, slop() + kEps);
  EXPECT_EQ(s.position.y, 0.0);
  EXPECT_EQ(s.velocity.x, 0.0);
}

// ---- restitution in a world ----
// A ball of radius 0.5 dropped with its bottom 1.25 m over the floor bounces to
// e^2 * 1.25 m. The bound, 1% of the drop, is loose on purpose here: the precise
// bounds are the stability suite's (tests/stability/restitution_test.cpp).
double first_bounce_apex(double restitution) {
  World world;
  add_or_fail(world, box_def({0.0, -0.5}, {50.0, 0.5}, Motion::Static));
  BodyDef def = circle_def({0.0, 1.75}, 0.5);
  def.restitution = restitution;
  const BodyId ball = add_or_fail(world, def);
  // The ball starts at rest and falls (v_y <= 0), so the first apex seen is the
  // top of the first bounce.
  ApexTracker apex(9.81);
  for (int step = 0; step < 240; ++step) {
    world.step(kDt);
    const BodyState s = *world.body(ball);
    if (apex.add(s.position.y - 0.5, s.velocity.y)) return apex.last_apex();
  }
  return 0.0;  // never bounced back up
}

TEST(WorldRestitution, ZeroStopsOnTheFloor) {
  World world;
  add_or_fail(world, box_def({0.0, -0.5}, {50.0, 0.5}, Motion::Static));
  const BodyId ball = add_or_fail(world, circle_def({0.0, 1.75}, 0.5));
  for (int step = 0; step < 240; ++step) {
    world.step(kDt);
    ASSERT_LE(world.body(ball)->velocity.y, 0.0) << "bounced at step " << step;
  }
  EXPECT_EQ(world.body(ball)->velocity.y, 0.0);
}

TEST(WorldRestitution, HalfBouncesToAQuarterOfTheHeight) {
  EXPECT_NEAR(first_bounce_apex(0.5), 0.25 * 1.25, 0.01 * 1.25);
}

TEST(WorldRestitution, OneBouncesBackToTheSameHeight) {
  EXPECT_NEAR(first_bounce_apex(1.0), 1.25, 0.01 * 1.25);
}

// ---- two dynamic bodies: masses 1 and 3 ----

class MassSplitting : public WorldTest {
 protected:
  void SetUp() override {
    WorldSettings settings;
    settings.gravity = {0.0, 0.0};
    settings.sleeping = false;
    reset(settings);
  }
};

TEST_F(MassSplitting, OverlapIsSeparatedInTheRatioOfInverseMasses) {
  // Radii 1 and 1, centres 1.6 apart: penetration 0.4. The light body moves three
  // times as far as the heavy one.
  const BodyId light = make_circle({0.0, 0.0}, 1.0, 1.0);
  const BodyId heavy = make_circle({1.6, 0.0}, 1.0, 3.0);
  world_.step(kDt);
  const double moved_light = position(light).x - 0.0;
  const double moved_heavy = position(heavy).x - 1.6;
  EXPECT_LT(moved_light, 0.0);
  EXPECT_GT(moved_heavy, 0.0);
  EXPECT_NEAR(moved_light, -3.0 * moved_heavy, 1e-12);
  const double gap = position(heavy).x - position(light).x;
  EXPECT_GE(gap, 2.0 - kEps);
  EXPECT_LE(gap, 2.0 + world_.settings().slop + kEps);
  // Moving apart is not a bounce: the momentum (zero) is unchanged.
  EXPECT_NEAR(1.0 * velocity(light).x + 3.0 * velocity(heavy).x, 0.0, 1e-12);
}

TEST_F(MassSplitting, ElasticHeadOnCollisionMatchesTheClosedForm) {
  // m1 = 1 at 4 m/s hits m2 = 3 at rest, e = 1: v1' = -2, v2' = 2; p = 4, E = 8.
  BodyDef a = circle_def({0.0, 0.0}, 0.5);
  a.velocity = {4.0, 0.0};
  a.restitution = 1.0;
  BodyDef b = circle_def({3.0, 0.0}, 0.5);
  b.mass = 3.0;
  b.restitution = 1.0;
  const BodyId light = add(a);
  const BodyId heavy = add(b);
  step_n(60);
  EXPECT_NEAR(velocity(light).x, -2.0, 1e-12);
  EXPECT_NEAR(velocity(heavy).x, 2.0, 1e-12);
  EXPECT_NEAR(1.0 * velocity(light).x + 3.0 * velocity(heavy).x, 4.0, 1e-12);
  EXPECT_NEAR(kinetic_energy(world_.bodies()), 8.0, 1e-11);
}

TEST_F(MassSplitting, InelasticBoxesMoveOnTogetherWithTheSameMomentum) {
  // m1 = 1 at 4 m/s hits m2 = 3 at rest, e = 0: both end at 1 m/s; p = 4.
  BodyDef a = box_def({0.0, 0.0}, {0.5, 0.5});
  a.velocity = {4.0, 0.0};
  BodyDef b = box_def({3.0, 0.0}, {0.5, 0.5});
  b.mass = 3.0;
  const BodyId light = add(a);
  const BodyId heavy = add(b);
  step_n(60);
  EXPECT_NEAR(velocity(light).x, 1.0, 1e-12);
  EXPECT_NEAR(velocity(heavy).x, 1.0, 1e-12);
  EXPECT_EQ(velocity(light).y, 0.0);
  EXPECT_EQ(position(light).y, 0.0);
  EXPECT_LE(overlap_depth(state(light), state(heavy)), 0.0);
}

TEST_F(MassSplitting, StaticBodiesNeverMove) {
  const BodyId wall = make_static_box({2.0, 0.0}, {0.5, 2.0});
  BodyDef def = circle_def({0.0, 0.0}, 0.5);
  def.velocity = {5.0, 0.0};
  def.mass = 1.0e6;
  add(def);
  step_n(60);
  EXPECT_EQ(position(wall), (Vec2{2.0, 0.0}));
  EXPECT_EQ(velocity(wall), (Vec2{}));
}

}  // namespace
}  // namespace phys::testing
