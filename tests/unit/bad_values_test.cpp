// Bad values are refused with the error that names the field at fault, and a
// refused body leaves the world as it was: NaN and infinite numbers, negative or
// zero sizes, non-positive masses of dynamic bodies, restitution and friction out
// of range, NaN accelerations through set_acceleration, bad settings.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <string_view>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// The largest |coordinate| of every world, as of the scene format.
constexpr double kMaxCoordinate = 1.0e7;

BodyDefError refusal(const BodyDef& def) {
  World world;
  BodyDefError error = BodyDefError::None;
  const BodyId id = world.add_body(def, &error);
  EXPECT_FALSE(id.is_valid());
  EXPECT_EQ(world.body_count(), 0u) << "a refused body was added";
  return error;
}

BodyDef good_box() { return box_def({0.0, 0.0}, {0.5, 0.5}); }
BodyDef good_circle() { return circle_def({0.0, 0.0}, 0.5); }

TEST(BadBodyDef, NaNPosition) {
  BodyDef def = good_box();
  def.position.x = kNaN;
  EXPECT_EQ(refusal(def), BodyDefError::NonFinitePosition);
}

TEST(BadBodyDef, InfinitePosition) {
  BodyDef def = good_circle();
  def.position.y = -kInf;
  EXPECT_EQ(refusal(def), BodyDefError::NonFinitePosition);
}

TEST(BadBodyDef, NaNVelocity) {
  BodyDef def = good_box();
  def.velocity.y = kNaN;
  EXPECT_EQ(refusal(def), BodyDefError::NonFiniteVelocity);
}

TEST(BadBodyDef, InfiniteAcceleration) {
  BodyDef def = good_box();
  def.acceleration.x = kInf;
  EXPECT_EQ(refusal(def), BodyDefError::NonFiniteAcceleration);
}

TEST(BadBodyDef, NegativeRadius) {
  BodyDef def = good_circle();
  def.radius = -0.5;
  EXPECT_EQ(refusal(def), BodyDefError::BadRadius);
}

TEST(BadBodyDef, ZeroAndNaNRadius) {
  BodyDef def = good_circle();
  def.radius = 0.0;
  EXPECT_EQ(refusal(def), BodyDefError::BadRadius);
  def.radius = kNaN;
  EXPECT_EQ(refusal(def), BodyDefError::BadRadius);
}

TEST(BadBodyDef, ZeroOrNegativeHalfExtents) {
  BodyDef def = good_box();
  def.half_extents = {0.0, 1.0};
  EXPECT_EQ(refusal(def), BodyDefError::BadHalfExtents);
  def.half_extents = {1.0, -1.0};
  EXPECT_EQ(refusal(def), BodyDefError::BadHalfExtents);
}

TEST(BadBodyDef, ZeroMassDynamic) {
  BodyDef def = good_box();
  def.mass = 0.0;
  EXPECT_EQ(refusal(def), BodyDefError::BadMass);
}

TEST(BadBodyDef, NegativeAndNaNMassDynamic) {
  BodyDef def = good_circle();
  def.mass = -1.0;
  EXPECT_EQ(refusal(def), BodyDefError::BadMass);
  def.mass = kNaN;
  EXPECT_EQ(refusal(def), BodyDefError::BadMass);
}

TEST(BadBodyDef, ZeroMassStaticIsFineBecauseStaticMassIsInfinite) {
  World world;
  BodyDef def = box_def({0.0, 0.0}, {1.0, 1.0}, Motion::Static);
  def.mass = 0.0;
  const BodyId id = add_or_fail(world, def);
  ASSERT_TRUE(id.is_valid());
  EXPECT_EQ(world.body(id)->mass, 0.0);  // reported as 0: infinite
}

TEST(BadBodyDef, RestitutionOutOfRange) {
  BodyDef def = good_box();
  def.restitution = 1.5;
  EXPECT_EQ(refusal(def), BodyDefError::BadRestitution);
  def.restitution = -0.1;
  EXPECT_EQ(refusal(def), BodyDefError::BadRestitution);
}

TEST(BadBodyDef, NegativeFriction) {
  BodyDef def = good_box();
  def.friction = {-1.0, 0.0};
  EXPECT_EQ(refusal(def), BodyDefError::BadFriction);
  def.friction = {0.0, kNaN};
  EXPECT_EQ(refusal(def), BodyDefError::BadFriction);
}

TEST(BadBodyDef, LargerThanTheSizeLimit) {
  BodyDef def = good_circle();
  def.radius = 2.0 * WorldSettings{}.max_body_size;
  EXPECT_EQ(refusal(def), BodyDefError::TooLarge);
}

TEST(BadBodyDef, OutsideTheBoundsWhenTheWorldHasBounds) {
  WorldSettings settings;
  settings.has_bounds = true;
  settings.bounds = {{-10.0, -10.0}, {10.0, 10.0}};
  World world(settings);
  BodyDefError error = BodyDefError::None;
  EXPECT_FALSE(world.add_body(box_def({50.0, 0.0}, {0.5, 0.5}), &error).is_valid());
  EXPECT_EQ(error, BodyDefError::OutOfBounds);
  EXPECT_TRUE(world.add_body(box_def({5.0, 0.0}, {0.5, 0.5}), &error).is_valid());
}

TEST(BadBodyDef, TooManyBodies) {
  WorldSettings settings;
  settings.max_bodies = 3;
  World world(settings);
  for (int i = 0; i < 3; ++i) add_or_fail(world, box_def({3.0 * i, 0.0}, {0.5, 0.5}));
  BodyDefError error = BodyDefError::None;
  EXPECT_FALSE(world.add_body(box_def({20.0, 0.0}, {0.5, 0.5}), &error).is_valid());
  EXPECT_EQ(error, BodyDefError::TooManyBodies);
  EXPECT_EQ(world.body_count(), 3u);
}

TEST(BadBodyDef, AKinematicBodyWithAnAccelerationIsRefused) {
  World world;
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5}, Motion::Kinematic);
  def.acceleration = {0.0, 1.0};
  BodyDefError error = BodyDefError::None;
  EXPECT_FALSE(world.add_body(def, &error).is_valid());
  EXPECT_EQ(error, BodyDefError::KinematicAcceleration);
  // Its mass is ignored (infinite), as a static body's; its velocity is checked.
  def.acceleration = {};
  def.mass = -1.0;
  def.velocity = {kNaN, 0.0};
  EXPECT_FALSE(world.add_body(def, &error).is_valid());
  EXPECT_EQ(error, BodyDefError::NonFiniteVelocity);
  def.velocity = {1.0, 0.0};
  EXPECT_TRUE(world.add_body(def, &error).is_valid());
}

TEST(BadBodyDef, ANameLongerThanTheLimitIsRefused) {
  World world;
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5});
  def.name = std::string(kMaxBodyNameBytes + 1, 'a');
  BodyDefError error = BodyDefError::None;
  EXPECT_FALSE(world.add_body(def, &error).is_valid());
  EXPECT_EQ(error, BodyDefError::BadName);
  def.name.pop_back();
  EXPECT_TRUE(world.add_body(def, &error).is_valid());
}

TEST(BadInputsKinematic, AStaticBodyTakesNoVelocityAKinematicOneTakesOnlyFiniteOnes) {
  World world;
  const BodyId wall = add_or_fail(world, box_def({0.0, 0.0}, {0.5, 0.5}, Motion::Static));
  const BodyId platform = add_or_fail(world, box_def({3.0, 0.0}, {0.5, 0.5}, Motion::Kinematic));
  EXPECT_FALSE(world.set_velocity(wall, {1.0, 0.0}));
  EXPECT_FALSE(world.set_velocity(platform, {kNaN, 0.0}));
  EXPECT_FALSE(world.set_velocity(platform, {0.0, kInf}));
  EXPECT_TRUE(world.set_velocity(platform, {1.0, 0.0}));
  EXPECT_FALSE(world.set_acceleration(platform, {1.0, 0.0}));
}

TEST(BadBodyDef, PositionBeyondTheCoordinateLimit) {
  for (const Vec2 far : {Vec2{-1.0e308, 0.0}, Vec2{1.0e308, 0.0}, Vec2{0.0, 1.0e7 * 1.0000001}}) {
    BodyDef def = good_circle();
    def.position = far;
    EXPECT_EQ(refusal(def), BodyDefError::OutOfBounds) << far.x << ", " << far.y;
  }
  BodyDef at_the_limit = good_box();
  at_the_limit.position = {-kMaxCoordinate, kMaxCoordinate};
  World world;
  EXPECT_TRUE(world.add_body(at_the_limit).is_valid());
}

// Two circles far apart in the same world once made the grid's cell-growing loop
// endless (their spread overflowed a double); now they are refused, and a step with
// the farthest accepted bodies returns.
TEST(BadBodyDef, BodiesAtPlusAndMinusTheLargestDoubleAreRefusedAndTheStepReturns) {
  World world;
  BodyDefError left = BodyDefError::None;
  BodyDefError right = BodyDefError::None;
  EXPECT_FALSE(world.add_body(circle_def({-1.0e308, 0.0}, 0.5), &left).is_valid());
  EXPECT_FALSE(world.add_body(circle_def({1.0e308, 0.0}, 0.5), &right).is_valid());
  EXPECT_EQ(left, BodyDefError::OutOfBounds);
  EXPECT_EQ(right, BodyDefError::OutOfBounds);
  ASSERT_TRUE(world.add_body(circle_def({-kMaxCoordinate, 0.0}, 0.5)).is_valid());
  ASSERT_TRUE(world.add_body(circle_def({kMaxCoordinate, 0.0}, 0.5)).is_valid());
  ASSERT_TRUE(world.add_body(circle_def({0.0, 0.0}, 0.5)).is_valid());
  for (int i = 0; i < 10; ++i) world.step(kDt);
  EXPECT_EQ(world.step_count(), 10u);
  EXPECT_TRUE(all_finite(world.bodies()));
}

TEST(BadBodyDef, RefusalWithoutAnErrorPointerDoesNotCrash) {
  World world;
  BodyDef def = good_box();
  def.mass = kNaN;
  EXPECT_FALSE(world.add_body(def).is_valid());
}

TEST(BadBodyDef, EveryErrorHasADescription) {
  for (const BodyDefError error :
       {BodyDefError::NonFinitePosition, BodyDefError::NonFiniteVelocity,
        BodyDefError::NonFiniteAcceleration, BodyDefError::BadRadius, BodyDefError::BadHalfExtents,
        BodyDefError::BadMass, BodyDefError::BadRestitution, BodyDefError::BadFriction,
        BodyDefError::OutOfBounds, BodyDefError::TooLarge, BodyDefError::TooManyBodies,
        BodyDefError::KinematicAcceleration, BodyDefError::BadName}) {
    EXPECT_FALSE(describe(error).empty());
    EXPECT_NE(describe(error), describe(BodyDefError::None));
  }
}

class BadInputs : public WorldTest {};

TEST_F(BadInputs, NaNAccelerationIsRefusedAndTheOldOneKept) {
  const BodyId id = make_box({0.0, 0.0});
  ASSERT_TRUE(world_.set_acceleration(id, {1.0, 2.0}));
  EXPECT_FALSE(world_.set_acceleration(id, {kNaN, 0.0}));
  EXPECT_FALSE(world_.set_acceleration(id, {0.0, kInf}));
  EXPECT_EQ(state(id).acceleration, (Vec2{1.0, 2.0}));
  world_.step(kDt);
  EXPECT_TRUE(all_finite(world_.bodies()));
}

TEST_F(BadInputs, NaNPositionAndVelocityAreRefused) {
  const BodyId id = make_box({1.0, 1.0});
  EXPECT_FALSE(world_.set_position(id, {kNaN, 0.0}));
  EXPECT_FALSE(world_.set_velocity(id, {0.0, -kInf}));
  EXPECT_EQ(state(id).position, (Vec2{1.0, 1.0}));
  EXPECT_EQ(state(id).velocity, (Vec2{}));
}

TEST_F(BadInputs, PositionBeyondTheCoordinateLimitIsRefused) {
  const BodyId id = make_box({1.0, 1.0});
  EXPECT_FALSE(world_.set_position(id, {1.0e308, 0.0}));
  EXPECT_FALSE(world_.set_position(id, {0.0, -2.0e7}));
  EXPECT_EQ(state(id).position, (Vec2{1.0, 1.0}));
  EXPECT_TRUE(world_.set_position(id, {kMaxCoordinate, 0.0}));
}

TEST_F(BadInputs, AccelerationMagnitudeIsClampedToTheLimit) {
  const BodyId id = make_box({0.0, 0.0});
  ASSERT_TRUE(world_.set_acceleration(id, {3.0e30, 4.0e30}));
  const Vec2 a = state(id).acceleration;
  EXPECT_NEAR(length(a), world_.settings().max_acceleration,
              1e-9 * world_.settings().max_acceleration);
  EXPECT_NEAR(a.x / a.y, 0.75, 1e-12);  // the direction is kept
}

TEST_F(BadInputs, StaticBodiesTakeNoAcceleration) {
  const BodyId wall = make_static_box({0.0, 0.0}, {1.0, 1.0});
  world_.set_acceleration(wall, {5.0, 0.0});
  world_.step(kDt);
  EXPECT_EQ(position(wall), (Vec2{0.0, 0.0}));
}

TEST(BadSettings, EachIsNamed) {
  WorldSettings s;
  EXPECT_EQ(check_settings(s), SettingsError::None);
  s.gravity.y = kNaN;
  EXPECT_EQ(check_settings(s), SettingsError::BadGravity);
  s.gravity.y = -1.0e7;  // finite, beyond kMaxGravity
  EXPECT_EQ(check_settings(s), SettingsError::BadGravity);
  s.gravity.y = -kMaxGravity;
  EXPECT_EQ(check_settings(s), SettingsError::None);
  s = {};
  s.substeps = 0;
  EXPECT_EQ(check_settings(s), SettingsError::BadSubsteps);
  s = {};
  s.slop = -1.0;
  EXPECT_EQ(check_settings(s), SettingsError::BadSlop);
  s = {};
  s.position_iterations = 0;
  EXPECT_EQ(check_settings(s), SettingsError::BadIterations);
  s = {};
  s.max_speed = 0.0;
  EXPECT_EQ(check_settings(s), SettingsError::BadSpeedLimit);
  s = {};
  s.sleep_time = -1.0;
  EXPECT_EQ(check_settings(s), SettingsError::BadSleep);
  s = {};
  s.has_bounds = true;
  s.bounds = {{1.0, 1.0}, {0.0, 2.0}};
  EXPECT_EQ(check_settings(s), SettingsError::BadBounds);
  EXPECT_NE(std::string_view(describe(SettingsError::BadBounds)), "");
}

}  // namespace
}  // namespace phys::testing
