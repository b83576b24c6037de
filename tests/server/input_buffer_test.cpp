// Input checks (window, NaN, clamp) and one client's buffer (filing, holding).
#include "server/input_buffer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using server::check_input;
using server::ClientInputs;
using server::InputVerdict;

constexpr std::uint64_t kAhead = 120;
constexpr double kMaxAccel = 50.0;

TEST(CheckInput, NextTickIsOnTime) {
  const auto check = check_input(11, {1.0, 2.0}, 10, kAhead, kMaxAccel);
  EXPECT_EQ(check.verdict, InputVerdict::OnTime);
  EXPECT_EQ(check.apply_at, 11u);
  EXPECT_FALSE(check.clamped);
  EXPECT_EQ(check.acceleration.x, 1.0);
  EXPECT_EQ(check.acceleration.y, 2.0);
}

TEST(CheckInput, TickAlreadySteppedIsLateAndGoesToTheNextTick) {
  for (const std::uint64_t tick : {0ull, 5ull, 10ull}) {
    const auto check = check_input(tick, {1.0, 0.0}, 10, kAhead, kMaxAccel);
    EXPECT_EQ(check.verdict, InputVerdict::Late) << tick;
    EXPECT_EQ(check.apply_at, 11u) << tick;
    EXPECT_TRUE(check.accepted());
  }
}

TEST(CheckInput, WindowEndsAtMaxTicksAhead) {
  EXPECT_EQ(check_input(10 + kAhead, {}, 10, kAhead, kMaxAccel).verdict, InputVerdict::OnTime);
  const auto far = check_input(10 + kAhead + 1, {}, 10, kAhead, kMaxAccel);
  EXPECT_EQ(far.verdict, InputVerdict::TooFarAhead);
  EXPECT_FALSE(far.accepted());
}

TEST(CheckInput, TickNearTheEndOfUint64DoesNotWrapIntoTheWindow) {
  const auto check =
      check_input(std::numeric_limits<std::uint64_t>::max(), {}, 10, kAhead, kMaxAccel);
  EXPECT_EQ(check.verdict, InputVerdict::TooFarAhead);
}

TEST(CheckInput, NanAndInfinityAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_input(11, {nan, 0.0}, 10, kAhead, kMaxAccel).verdict, InputVerdict::NonFinite);
  EXPECT_EQ(check_input(11, {0.0, nan}, 10, kAhead, kMaxAccel).verdict, InputVerdict::NonFinite);
  EXPECT_EQ(check_input(11, {inf, 0.0}, 10, kAhead, kMaxAccel).verdict, InputVerdict::NonFinite);
  EXPECT_EQ(check_input(11, {0.0, -inf}, 10, kAhead, kMaxAccel).verdict, InputVerdict::NonFinite);
  EXPECT_FALSE(check_input(11, {nan, nan}, 10, kAhead, kMaxAccel).accepted());
}

TEST(CheckInput, MagnitudeIsClampedKeepingDirection) {
  const auto check = check_input(11, {300.0, 400.0}, 10, kAhead, kMaxAccel);  // |a| = 500
  EXPECT_TRUE(check.clamped);
  EXPECT_DOUBLE_EQ(check.acceleration.x, 30.0);
  EXPECT_DOUBLE_EQ(check.acceleration.y, 40.0);
}

TEST(CheckInput, HugeFiniteValuesClampWithoutOverflow) {
  const double big = std::numeric_limits<double>::max();
  const auto check = check_input(11, {big, -big}, 10, kAhead, kMaxAccel);
  ASSERT_EQ(check.verdict, InputVerdict::OnTime);
  EXPECT_TRUE(check.clamped);
  EXPECT_TRUE(std::isfinite(check.acceleration.x));
  EXPECT_NEAR(std::hypot(check.acceleration.x, check.acceleration.y), kMaxAccel, 1e-9);
  EXPECT_GT(check.acceleration.x, 0.0);
  EXPECT_LT(check.acceleration.y, 0.0);
}

TEST(CheckInput, MagnitudeAtTheLimitIsNotClamped) {
  const auto check = check_input(11, {30.0, 40.0}, 10, kAhead, kMaxAccel);
  EXPECT_FALSE(check.clamped);
  EXPECT_EQ(check.acceleration.x, 30.0);
}

TEST(ClientInputs, InputHoldsUntilTheNextOne) {
  ClientInputs inputs;
  inputs.file(3, 3, {1.0, 0.0});
  EXPECT_FALSE(inputs.take(1).fresh);
  EXPECT_EQ(inputs.take(2).acceleration.x, 0.0);
  const auto at3 = inputs.take(3);
  EXPECT_TRUE(at3.fresh);
  EXPECT_EQ(at3.acceleration.x, 1.0);
  for (std::uint64_t tick = 4; tick < 10; ++tick) {
    const auto held = inputs.take(tick);
    EXPECT_FALSE(held.fresh);
    EXPECT_EQ(held.acceleration.x, 1.0);
  }
  inputs.file(10, 10, {0.0, -2.0});
  const auto at10 = inputs.take(10);
  EXPECT_TRUE(at10.fresh);
  EXPECT_EQ(at10.acceleration.x, 0.0);
  EXPECT_EQ(at10.acceleration.y, -2.0);
  EXPECT_EQ(inputs.last_applied_tick(), 10u);
}

TEST(ClientInputs, OnTimeInputBeatsALateOneFiledAtTheSameTick) {
  ClientInputs inputs;
  inputs.file(11, 11, {1.0, 0.0});  // on time for 11
  inputs.file(11, 8, {9.0, 0.0});   // late (named 8), refiled at 11
  const auto taken = inputs.take(11);
  EXPECT_EQ(taken.acceleration.x, 1.0);
  EXPECT_EQ(inputs.last_applied_tick(), 11u);

  ClientInputs other;
  other.file(11, 8, {9.0, 0.0});
  other.file(11, 11, {1.0, 0.0});
  EXPECT_EQ(other.take(11).acceleration.x, 1.0);
}

TEST(ClientInputs, ASecondInputForTheSameTickReplacesTheFirst) {
  ClientInputs inputs;
  inputs.file(5, 5, {1.0, 0.0});
  inputs.file(5, 5, {2.0, 0.0});
  EXPECT_EQ(inputs.pending_count(), 1u);
  EXPECT_EQ(inputs.take(5).acceleration.x, 2.0);
}

TEST(ClientInputs, ReportsWhetherAnInputIsDue) {
  ClientInputs inputs;
  EXPECT_FALSE(inputs.has_input_for(1));
  inputs.file(3, 3, {1.0, 0.0});
  EXPECT_FALSE(inputs.has_input_for(2));
  EXPECT_TRUE(inputs.has_input_for(3));
  EXPECT_FALSE(inputs.has_applied());
  inputs.take(3);
  EXPECT_TRUE(inputs.has_applied());
  EXPECT_FALSE(inputs.has_input_for(3));
}

// A million inputs inside a window of a million ticks, filed in the worst order (from
// the far end back): one slot a tick, 32 bytes each, and all of it is given back as
// the ticks are taken.
TEST(ClientInputs, AFullWindowIsBoundedAndItsMemoryComesBack) {
  constexpr std::uint64_t kWindow = 1000000;
  ClientInputs inputs;
  for (std::uint64_t tick = kWindow; tick >= 1; --tick) {
    inputs.file(tick, tick, {static_cast<double>(tick % 7), 0.0});
  }
  EXPECT_EQ(inputs.pending_count(), kWindow);
  EXPECT_LE(inputs.memory_bytes(), kWindow * 32);
  // The same ticks again, newest wins: no growth.
  for (std::uint64_t tick = 1; tick <= kWindow; ++tick) inputs.file(tick, tick, {1.0, 0.0});
  EXPECT_EQ(inputs.pending_count(), kWindow);
  EXPECT_LE(inputs.memory_bytes(), kWindow * 32);
  inputs.take(kWindow / 2);
  EXPECT_EQ(inputs.pending_count(), kWindow / 2);
  EXPECT_LE(inputs.memory_bytes(), kWindow / 2 * 32);
  EXPECT_EQ(inputs.take(kWindow).acceleration.x, 1.0);
  EXPECT_EQ(inputs.pending_count(), 0u);
  EXPECT_EQ(inputs.memory_bytes(), 0u);
}

// The span, not the count, is what a slot a tick costs: two inputs a window apart
// hold the window until the first is taken, then only the second.
TEST(ClientInputs, EmptyTicksBeforeTheNextInputAreNotKept) {
  ClientInputs inputs;
  inputs.file(10, 10, {1.0, 0.0});
  inputs.file(1010, 1010, {2.0, 0.0});
  EXPECT_EQ(inputs.pending_count(), 2u);
  EXPECT_EQ(inputs.memory_bytes(), 1001 * 32u);
  EXPECT_TRUE(inputs.take(10).fresh);
  EXPECT_EQ(inputs.memory_bytes(), 32u);
  EXPECT_FALSE(inputs.has_input_for(1009));
  EXPECT_TRUE(inputs.has_input_for(1010));
  // An input for a tick before the pending one grows the front.
  inputs.file(500, 500, {3.0, 0.0});
  EXPECT_TRUE(inputs.has_input_for(500));
  EXPECT_EQ(inputs.take(600).acceleration.x, 3.0);
  EXPECT_EQ(inputs.take(1010).acceleration.x, 2.0);
}

}  // namespace
