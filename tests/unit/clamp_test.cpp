// The clamp of speeds and accelerations (clamp_length, vec2.h), alone and through
// every way into the world: set_velocity, set_acceleration and a BodyDef. Bound:
// a vector over the limit comes back with its direction kept (the ratio of its
// components within 4 ulps, DOUBLE_EQ; exact when the ratio is a power of two) and
// its length within 2 ulps of the limit (exactly the limit along an axis, and
// where the scaled vector is a 3-4-5 triangle), for every magnitude up to DBL_MAX:
// length(v) overflows past about 1.3e154, which once clamped such vectors to (0, 0).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

constexpr double kMaxSpeed = WorldSettings{}.max_speed;                // 1000 m/s
constexpr double kMaxAcceleration = WorldSettings{}.max_acceleration;  // 1e5 m/s^2
constexpr double kHuge = std::numeric_limits<double>::max();

struct OverLimit {
  const char* name;
  Vec2 v;
  // The clamped value as a multiple of the limit, where it is exact.
  std::optional<Vec2> exact_per_limit;
};

const OverLimit kOverLimit[] = {
    {"1e200_along_x", {1.0e200, 0.0}, Vec2{1.0, 0.0}},
    {"1e200_diagonal", {1.0e200, 1.0e200}, std::nullopt},
    {"1e300_mixed_signs", {1.0e300, -1.0e300}, std::nullopt},
    {"minus_1e308_along_x", {-1.0e308, 0.0}, Vec2{-1.0, 0.0}},
    {"minus_1e308_along_y", {0.0, -1.0e308}, Vec2{0.0, -1.0}},
    {"minus_1e308_diagonal", {-1.0e308, -1.0e308}, std::nullopt},
    {"minus_1e308_half", {-1.0e308, 5.0e307}, std::nullopt},
    {"mixed_signs_3_4_5", {-3.0e250, 4.0e250}, Vec2{-0.6, 0.8}},
    {"uneven_mixed_signs", {1.0e200, -7.0e199}, std::nullopt},
    {"dbl_max_diagonal", {kHuge, -kHuge}, std::nullopt},
    {"normal_3_4_5", {3.0e6, -4.0e6}, Vec2{0.6, -0.8}},
    {"normal_uneven", {123456.5, -98765.25}, std::nullopt},
};

// The length of v, in long double (its range holds the square of DBL_MAX), so
// that this measurement does not share the clamp's scaling.
long double true_length(Vec2 v) {
  return std::hypot(static_cast<long double>(v.x), static_cast<long double>(v.y));
}

void expect_clamped(Vec2 original, Vec2 clamped, double limit, const OverLimit& c,
                    bool exact = true) {
  const double ulp = std::nextafter(limit, kHuge) - limit;
  EXPECT_LE(std::abs(true_length(clamped) - static_cast<long double>(limit)),
            2.0L * static_cast<long double>(ulp))
      << "length " << static_cast<double>(true_length(clamped)) << ", limit " << limit;
  EXPECT_DOUBLE_EQ(static_cast<double>(true_length(clamped)), limit);
  // The direction: same signs, same ratio of the components.
  EXPECT_EQ(std::signbit(clamped.x), std::signbit(original.x)) << clamped.x;
  EXPECT_EQ(std::signbit(clamped.y), std::signbit(original.y)) << clamped.y;
  if (original.y == 0.0) {
    EXPECT_EQ(clamped.y, 0.0);
  } else {
    EXPECT_DOUBLE_EQ(clamped.x / clamped.y, original.x / original.y);
  }
  if (exact && c.exact_per_limit) {
    EXPECT_EQ(clamped.x, c.exact_per_limit->x * limit);
    EXPECT_EQ(clamped.y, c.exact_per_limit->y * limit);
  }
}

class ClampOverLimit : public ::testing::TestWithParam<OverLimit> {};

TEST_P(ClampOverLimit, ClampLengthKeepsDirectionAndLandsOnTheLimit) {
  const OverLimit& c = GetParam();
  for (const double limit : {kMaxSpeed, kMaxAcceleration, 1.0, 1.0e200}) {
    SCOPED_TRACE(limit);
    if (true_length(c.v) <= static_cast<long double>(limit)) continue;
    bool clamped = false;
    const Vec2 out = clamp_length(c.v, limit, &clamped);
    EXPECT_TRUE(clamped);
    // (Exact values are known for the world's limits, 1000 and 1e5.)
    expect_clamped(c.v, out, limit, c, limit == kMaxSpeed || limit == kMaxAcceleration);
    // Clamping again changes nothing: the server's input check and the world's
    // setter may both clamp one acceleration.
    bool again = true;
    EXPECT_EQ(clamp_length(out, limit, &again), out);
    EXPECT_FALSE(again);
  }
}

TEST_P(ClampOverLimit, SetVelocityStoresTheLimit) {
  const OverLimit& c = GetParam();
  World world;
  const BodyId id = add_or_fail(world, circle_def({0.0, 0.0}, 0.5));
  ASSERT_TRUE(world.set_velocity(id, c.v));
  expect_clamped(c.v, world.body(id)->velocity, kMaxSpeed, c);
  EXPECT_EQ(world.counters().speed_clamps, 1u);
}

TEST_P(ClampOverLimit, SetAccelerationStoresTheLimit) {
  const OverLimit& c = GetParam();
  World world;
  const BodyId id = add_or_fail(world, circle_def({0.0, 0.0}, 0.5));
  ASSERT_TRUE(world.set_acceleration(id, c.v));
  expect_clamped(c.v, world.body(id)->acceleration, kMaxAcceleration, c);
  EXPECT_EQ(world.counters().acceleration_clamps, 1u);
}

TEST_P(ClampOverLimit, BodyDefinitionIsClampedToo) {
  const OverLimit& c = GetParam();
  World world;
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5});
  def.velocity = c.v;
  def.acceleration = c.v;
  const BodyId id = add_or_fail(world, def);
  expect_clamped(c.v, world.body(id)->velocity, kMaxSpeed, c);
  expect_clamped(c.v, world.body(id)->acceleration, kMaxAcceleration, c);
  EXPECT_EQ(world.counters().speed_clamps, 1u);
  EXPECT_EQ(world.counters().acceleration_clamps, 1u);
}

TEST_P(ClampOverLimit, TheClampedBodyMovesAtTheLimit) {
  // Zero gravity, no friction: one step moves the body by max_speed * dt along
  // the original direction (Exact integrator, so v * dt exactly, to rounding).
  const OverLimit& c = GetParam();
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  World world(settings);
  const BodyId id = add_or_fail(world, circle_def({0.0, 0.0}, 0.5));
  ASSERT_TRUE(world.set_velocity(id, c.v));
  world.step(kDt);
  const Vec2 moved = world.body(id)->position;
  EXPECT_NEAR(static_cast<double>(true_length(moved)), kMaxSpeed * kDt, 1.0e-12);
  expect_clamped(c.v, world.body(id)->velocity, kMaxSpeed, c);
}

INSTANTIATE_TEST_SUITE_P(Vectors, ClampOverLimit, ::testing::ValuesIn(kOverLimit),
                         [](const auto& case_info) { return std::string(case_info.param.name); });

TEST(Clamp, AtOrUnderTheLimitIsUnchangedAndUncounted) {
  World world;
  const BodyId id = add_or_fail(world, circle_def({0.0, 0.0}, 0.5));
  for (const Vec2 v : std::vector<Vec2>{
           {600.0, -800.0}, {-1000.0, 0.0}, {0.0, 999.9}, {0.0, 0.0}, {1.0e-300, -1.0e-310}}) {
    ASSERT_TRUE(world.set_velocity(id, v));
    EXPECT_EQ(world.body(id)->velocity, v);
    bool clamped = true;
    EXPECT_EQ(clamp_length(v, kMaxSpeed, &clamped), v);
    EXPECT_FALSE(clamped);
  }
  EXPECT_EQ(world.counters().speed_clamps, 0u);
}

TEST(Clamp, LengthWithoutOverflowIsTheLength) {
  EXPECT_EQ(length_without_overflow({3.0e300, -4.0e300}), 5.0e300);
  EXPECT_EQ(length_without_overflow({-1.0e308, 0.0}), 1.0e308);
  EXPECT_EQ(length_without_overflow({3.0, 4.0}), 5.0);
  EXPECT_EQ(length_without_overflow({0.0, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(length_without_overflow({1.0e200, 1.0e200}), std::sqrt(2.0) * 1.0e200);
}

TEST(Clamp, AStepUnderAHugeSpeedLimitKeepsAHugeVelocity) {
  // max_speed may be any finite number: under 1e300, a body at 1e200 m/s along
  // both axes is within the limit, and the step's own speed check (whose squared
  // speed overflows) must not stop it.
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  settings.max_speed = 1.0e300;
  World world(settings);
  const BodyId id = add_or_fail(world, circle_def({0.0, 0.0}, 0.5));
  const Vec2 v{1.0e200, -1.0e200};
  ASSERT_TRUE(world.set_velocity(id, v));
  ASSERT_EQ(world.body(id)->velocity, v);
  world.step(kDt);
  EXPECT_DOUBLE_EQ(world.body(id)->velocity.x, v.x);
  EXPECT_DOUBLE_EQ(world.body(id)->velocity.y, v.y);
  EXPECT_DOUBLE_EQ(world.body(id)->position.x, v.x * kDt);
  EXPECT_DOUBLE_EQ(world.body(id)->position.y, v.y * kDt);
}

}  // namespace
}  // namespace phys::testing

namespace phys::testing {
namespace {

TEST(Clamp, ABounceUnderAHugeGravityStaysUnderTheSpeedLimit) {
  // A swept bounce re-integrates the rest of its sub-step from the contact: under
  // 13,000 g the box leaves the floor faster than max_speed unless the bounce is
  // capped as the free motion is. Its state must stay one the world can hold (and
  // World::from_bytes read back).
  WorldSettings settings;
  settings.gravity = {0.0, -131072.0};
  settings.max_speed = 1000.0;
  settings.rest_speed = 1.0;
  World world(settings);
  BodyDef ground = box_def({0.0, -0.5}, {10.0, 0.5});
  ground.motion = Motion::Static;
  add_or_fail(world, ground);
  BodyDef box = box_def({-1.0, 0.82}, {0.2, 0.2});
  box.restitution = 0.5;
  const BodyId id = add_or_fail(world, box);
  const std::uint64_t clamps_before = world.counters().speed_clamps;
  for (int i = 0; i < 30; ++i) {
    world.step(kDt);
    const Vec2 v = world.body(id)->velocity;
    ASSERT_LE(std::fabs(v.x), settings.max_speed) << "step " << i;
    ASSERT_LE(std::fabs(v.y), settings.max_speed) << "step " << i;
    std::string error;
    ASSERT_TRUE(World::from_bytes(world.to_bytes(), &error).has_value()) << error;
  }
  EXPECT_GT(world.counters().speed_clamps, clamps_before);
}

}  // namespace
}  // namespace phys::testing
