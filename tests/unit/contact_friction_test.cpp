// Coulomb contact friction (beyond the classic recipe): a contact's tangential impulse is at
// most mu times its normal impulse, mu mixed sqrt(a*b). A box sliding on a floor then
// decelerates at mu*g and stops after v^2 / (2 mu g); with mu = 0 nothing changes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "physics/formulas.h"
#include "physics_test_support.h"

namespace phys::testing {
namespace {

constexpr double kGravity = 9.81;

struct Slide {
  double distance;
  double final_speed;
};

// A unit box at 5 m/s along a long static floor, both with the given mu, for 3 s.
Slide slide_box(double mu_box, double mu_floor) {
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  BodyDef floor = box_def({0.0, -1.0}, {100.0, 1.0}, Motion::Static);
  floor.contact_friction = mu_floor;
  add_or_fail(world, floor);
  BodyDef box = box_def({0.0, 0.5}, {0.5, 0.5});
  box.velocity = {5.0, 0.0};
  box.contact_friction = mu_box;
  const BodyId id = add_or_fail(world, box);
  for (int step = 0; step < 180; ++step) world.step(kDt);
  const BodyState state = *world.body(id);
  return {state.position.x, std::fabs(state.velocity.x)};
}

TEST(ContactFriction, MixesAsTheSquareRootOfTheProduct) {
  EXPECT_DOUBLE_EQ(mix_contact_friction(0.25, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(mix_contact_friction(0.0, 1.0), 0.0);
}

TEST(ContactFriction, SlidingBoxStopsAfterTheClosedFormDistanceWithinAStepOfTravel) {
  const double mu = 0.5;
  const double expected = 5.0 * 5.0 / (2.0 * mu * kGravity);  // 2.548 m
  const Slide slide = slide_box(mu, mu);
  EXPECT_EQ(slide.final_speed, 0.0);
  // The discrete slide overshoots the closed form by about one step of travel
  // (v0 * dt = 0.083 m): friction acts as an impulse at the end of each step, so the
  // position lags the continuous one by half a step of travel, and the first contact
  // step carries half the normal impulse (the push out of the floor already cancelled
  // half the approach speed), another half step. Measured: 0.093 m. Bound: 1.5 steps.
  EXPECT_GT(slide.distance, expected);
  EXPECT_LT(slide.distance - expected, 1.5 * 5.0 * kDt);
}

TEST(ContactFriction, ZeroFrictionOnEitherSideKeepsTheSpeed) {
  const Slide slide = slide_box(0.0, 0.5);  // sqrt(0 * 0.5) = 0
  EXPECT_NEAR(slide.final_speed, 5.0, 1e-9);
  EXPECT_NEAR(slide.distance, 5.0 * 3.0, 1e-6);
}

// A floor and a column of 10 unit boxes on it, all with mu = 0.5; the bottom box is
// pushed sideways at `share` of what the column's weight lets friction hold.
BodyId add_pushed_column(World& world, double share) {
  const double mu = 0.5;
  BodyDef floor = box_def({0.0, -1.0}, {100.0, 1.0}, Motion::Static);
  floor.contact_friction = mu;
  add_or_fail(world, floor);
  BodyId bottom{};
  for (int level = 0; level < 10; ++level) {
    BodyDef box = box_def({0.0, 0.5 + level}, {0.5, 0.5});
    box.contact_friction = mu;
    if (level == 0) box.acceleration = {share * mu * 10.0 * kGravity, 0.0};
    const BodyId id = add_or_fail(world, box);
    if (level == 0) bottom = id;
  }
  return bottom;
}

// Coulomb's law under load: the friction that holds a body is bounded by the whole
// normal force on it, including the weight of what rests on it. A unit box on the
// floor carries a column of 9 more (all mu = 0.5) and is pushed sideways at
// 24.5 m/s^2: half of what the column's weight lets friction hold (mu * 10 * g =
// 49 m/s^2 of the bottom box's mass), five times what the box's own weight alone
// would (4.9). It must not move. Shock propagation keeps the column's weight out of
// the bottom box's contact impulses; without the load put back into its friction
// (Body::load) it slid by 1.2 m, and without the push held in the next step's move
// (Body::held, per axis) it crept by a*dt*dt/2 = 3.4 mm a step. The load is known
// from the step after the contacts are first solved, so the box slips in its first
// steps (measured 0.033 m); from 0.1 s on, bound: less than 1 mm over 5 s.
TEST(ContactFriction, LoadedBoxHoldsAPushThatItsOwnWeightCouldNot) {
  World world;
  const BodyId bottom = add_pushed_column(world, 0.5);
  for (int step = 0; step < 6; ++step) world.step(kDt);
  const double after_start = world.body(bottom)->position.x;
  EXPECT_LT(after_start, 0.05);
  for (int step = 0; step < 300; ++step) world.step(kDt);
  EXPECT_LT(std::fabs(world.body(bottom)->position.x - after_start), 1.0e-3);
}

// And the load holds no more than Coulomb allows: pushed at 1.2 times what the
// column's weight holds (58.9 m/s^2), the bottom box slides out from under it.
TEST(ContactFriction, LoadedBoxSlidesUnderAPushBeyondItsLoad) {
  World world;
  const BodyId bottom = add_pushed_column(world, 1.2);
  for (int step = 0; step < 60; ++step) world.step(kDt);
  EXPECT_GT(world.body(bottom)->position.x, 0.5);
}

TEST(ContactFriction, NegativeOrNonFiniteFrictionIsRefused) {
  World world;
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5});
  for (double bad : {-0.1, std::nan(""), std::numeric_limits<double>::infinity()}) {
    def.contact_friction = bad;
    BodyDefError error = BodyDefError::None;
    EXPECT_FALSE(world.add_body(def, &error).is_valid()) << bad;
    EXPECT_EQ(error, BodyDefError::BadFriction) << bad;
  }
}

// Candidate pairs are reused while every body stays inside the box its pairs were
// found with: a resting stack finds its pairs once, then reuses them.
TEST(BroadphaseReuse, RestingStackReusesItsCandidatePairs) {
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  add_or_fail(world, box_def({0.0, -1.0}, {10.0, 1.0}, Motion::Static));
  for (int i = 0; i < 10; ++i) add_or_fail(world, box_def({0.0, 0.5 + i}, {0.5, 0.5}));
  for (int step = 0; step < 120; ++step) world.step(kDt);
  EXPECT_GT(world.counters().broadphase_reuses, 100u);
}

TEST(BroadphaseReuse, FallingBodiesFindNewPairsEveryStep) {
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  for (int i = 0; i < 10; ++i) add_or_fail(world, circle_def({2.0 * i, 100.0}, 0.5));
  for (int step = 0; step < 60; ++step) world.step(kDt);
  // Falling faster every step, each body leaves the box its pairs were found with.
  EXPECT_LT(world.counters().broadphase_reuses, 30u);
}

}  // namespace
}  // namespace phys::testing
