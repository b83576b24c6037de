// The accumulator of the fixed-timestep driver, driven by a ManualClock: exactly N
// updates for N periods elapsed, the per-frame cap with the dropped backlog
// counted, and the leftover fraction alpha.
#include "physics/fixed_timestep.h"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "physics/clock.h"

namespace phys {
namespace {

using std::chrono::nanoseconds;

class Accumulator : public ::testing::Test {
 protected:
  // Runs one frame, recording every dt handed to the update.
  FrameResult frame() {
    return driver_.frame([this](double dt) { dts_.push_back(dt); });
  }

  ManualClock clock_;
  FixedTimestep driver_{clock_, FixedTimestepConfig{60.0, 6}};
  std::vector<double> dts_;
};

TEST_F(Accumulator, DefaultsAreSixtyHertzAndSixSteps) {
  const FixedTimestepConfig defaults;
  EXPECT_EQ(defaults.tick_rate_hz, 60.0);
  EXPECT_EQ(defaults.max_steps_per_frame, 6);
}

TEST_F(Accumulator, DtIsExactlyOneOverTheRate) {
  EXPECT_EQ(driver_.dt(), 1.0 / 60.0);
  // The period in whole nanoseconds is within half a nanosecond of 1/60 s.
  EXPECT_NEAR(static_cast<double>(driver_.period().count()), 1.0e9 / 60.0, 0.5);
}

TEST_F(Accumulator, NoTimeNoUpdate) {
  const FrameResult result = frame();
  EXPECT_EQ(result.steps, 0);
  EXPECT_TRUE(dts_.empty());
  EXPECT_EQ(driver_.alpha(), 0.0);
}

TEST_F(Accumulator, JustUnderOnePeriodRunsNothing) {
  clock_.advance(driver_.period() - nanoseconds(1));
  EXPECT_EQ(frame().steps, 0);
  EXPECT_TRUE(dts_.empty());
}

TEST_F(Accumulator, ExactlyOnePeriodRunsOneUpdateWithDt) {
  clock_.advance(driver_.period());
  EXPECT_EQ(frame().steps, 1);
  ASSERT_EQ(dts_.size(), 1u);
  EXPECT_EQ(dts_[0], 1.0 / 60.0);
  EXPECT_EQ(driver_.alpha(), 0.0);
}

TEST_F(Accumulator, NPeriodsInOneFrameRunNUpdates) {
  for (int n = 1; n <= 6; ++n) {
    dts_.clear();
    clock_.advance(driver_.period() * n);
    const FrameResult result = frame();
    EXPECT_EQ(result.steps, n);
    EXPECT_EQ(result.dropped_steps, 0u);
    EXPECT_EQ(dts_.size(), static_cast<std::size_t>(n));
  }
  EXPECT_EQ(driver_.total_steps(), 21u);  // 1 + 2 + ... + 6
}

TEST_F(Accumulator, TenThousandFramesOfOnePeriodRunExactlyTenThousandUpdates) {
  for (int i = 0; i < 10'000; ++i) {
    clock_.advance(driver_.period());
    ASSERT_EQ(frame().steps, 1) << "frame " << i;
  }
  EXPECT_EQ(driver_.total_steps(), 10'000u);
  EXPECT_EQ(driver_.total_dropped_steps(), 0u);
}

TEST_F(Accumulator, SmallFramesAddUpWithoutLosingTime) {
  // 600 periods elapsed in frames of a third of a period (the remainder of the
  // division goes into the last frame): exactly 600 updates, whatever the split.
  const nanoseconds total = driver_.period() * 600;
  const nanoseconds third = driver_.period() / 3;
  nanoseconds elapsed{0};
  while (elapsed + third <= total) {
    clock_.advance(third);
    elapsed += third;
    frame();
  }
  clock_.advance(total - elapsed);
  frame();
  EXPECT_EQ(driver_.total_steps(), 600u);
  EXPECT_EQ(driver_.alpha(), 0.0);
}

TEST_F(Accumulator, CapsStepsPerFrameAndCountsTheDroppedBacklog) {
  clock_.advance(driver_.period() * 10);
  const FrameResult result = frame();
  EXPECT_EQ(result.steps, 6);
  EXPECT_EQ(result.dropped_steps, 4u);
  EXPECT_EQ(dts_.size(), 6u);
  EXPECT_EQ(driver_.total_dropped_steps(), 4u);
}

TEST_F(Accumulator, AfterTheCapTheNextFrameDoesNotCatchUp) {
  clock_.advance(driver_.period() * 10);
  frame();
  clock_.advance(driver_.period());
  const FrameResult result = frame();
  EXPECT_EQ(result.steps, 1);
  EXPECT_EQ(result.dropped_steps, 0u);
  EXPECT_EQ(driver_.total_steps(), 7u);
}

TEST_F(Accumulator, AlphaIsTheLeftoverFraction) {
  clock_.advance(driver_.period() * 2 + driver_.period() / 4);
  EXPECT_EQ(frame().steps, 2);
  EXPECT_NEAR(driver_.alpha(), 0.25, 1e-7);  // whole nanoseconds: within 1e-7
  clock_.advance(driver_.period() / 2);
  EXPECT_EQ(frame().steps, 0);
  EXPECT_NEAR(driver_.alpha(), 0.75, 1e-7);
  clock_.advance(driver_.period() / 4 + nanoseconds(2));
  EXPECT_EQ(frame().steps, 1);
  EXPECT_LT(driver_.alpha(), 1e-6);
}

TEST_F(Accumulator, AlphaStaysBelowOneAfterACappedFrame) {
  clock_.advance(driver_.period() * 10 + driver_.period() / 2);
  frame();
  EXPECT_GE(driver_.alpha(), 0.0);
  EXPECT_LT(driver_.alpha(), 1.0);
}

TEST_F(Accumulator, NextStepDueIsOnePeriodAheadOfTheLastWholeStep) {
  clock_.advance(driver_.period() + driver_.period() / 2);
  frame();
  // Half a period is left in the accumulator: the next step is due half a period
  // from now (whole nanoseconds, so within 1 ns).
  const auto due = driver_.next_step_due();
  const auto expected = clock_.now() + (driver_.period() - driver_.period() / 2);
  EXPECT_LE(std::chrono::abs(due - expected), nanoseconds(1));
}

TEST(AccumulatorConfig, OtherRatesAndCaps) {
  ManualClock clock;
  FixedTimestep driver(clock, FixedTimestepConfig{100.0, 2});
  EXPECT_EQ(driver.dt(), 0.01);
  EXPECT_EQ(driver.period(), nanoseconds(10'000'000));
  clock.advance(nanoseconds(50'000'000));  // 5 periods
  int updates = 0;
  const FrameResult result = driver.frame([&](double) { ++updates; });
  EXPECT_EQ(updates, 2);
  EXPECT_EQ(result.dropped_steps, 3u);
}

}  // namespace
}  // namespace phys
