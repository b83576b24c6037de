// The spiral of death. A ManualClock jumps 10 s forward while a world
// is driven by the fixed-timestep driver (60 Hz, at most 6 steps a frame).
// Bounds: that frame runs exactly 6 steps, the other whole steps of the backlog
// are dropped and counted, and afterwards one frame per period runs exactly one
// step again (real time is kept, nothing is caught up); the world stays finite.
#include <gtest/gtest.h>

#include <chrono>

#include "physics/clock.h"
#include "physics/fixed_timestep.h"
#include "stability_scenes.h"

namespace phys::testing {
namespace {

using std::chrono::nanoseconds;

class SpiralOfDeath : public ::testing::Test {
 protected:
  void SetUp() override {
    add_column(world_, {0.0, 0.0}, std::vector<double>(5, 1.0));
    add_dropped_ball(world_, {10.0, 0.0}, 5.0, 0.5);
  }
  FrameResult frame() {
    return driver_.frame([this](double dt) { world_.step(dt); });
  }
  void real_time_frames(int count) {
    for (int i = 0; i < count; ++i) {
      clock_.advance(driver_.period());
      ASSERT_EQ(frame().steps, 1) << "frame " << i;
    }
  }

  ManualClock clock_;
  FixedTimestep driver_{clock_, FixedTimestepConfig{60.0, 6}};
  World world_;
};

TEST_F(SpiralOfDeath, TenSecondJumpRunsTheCapDropsTheRestThenKeepsRealTime) {
  real_time_frames(60);
  const nanoseconds jump = std::chrono::seconds(10);
  const auto whole_steps = static_cast<std::uint64_t>(jump / driver_.period());
  clock_.advance(jump);
  const FrameResult jumped = frame();
  EXPECT_EQ(jumped.steps, 6);
  EXPECT_EQ(jumped.dropped_steps, whole_steps - 6);
  EXPECT_EQ(driver_.total_dropped_steps(), whole_steps - 6);
  EXPECT_GE(driver_.alpha(), 0.0);
  EXPECT_LT(driver_.alpha(), 1.0);
  real_time_frames(120);
  EXPECT_EQ(driver_.total_steps(), 60u + 6u + 120u);
  EXPECT_EQ(world_.step_count(), 60u + 6u + 120u);
  EXPECT_EQ(driver_.total_dropped_steps(), whole_steps - 6);
  EXPECT_TRUE(all_finite(world_.bodies()));
}

TEST_F(SpiralOfDeath, RepeatedJumpsNeverRunMoreThanTheCap) {
  std::uint64_t expected_dropped = 0;
  for (int i = 0; i < 100; ++i) {
    clock_.advance(std::chrono::seconds(10));
    const FrameResult result = frame();
    ASSERT_EQ(result.steps, 6);
    expected_dropped += result.dropped_steps;
  }
  EXPECT_EQ(driver_.total_steps(), 600u);
  EXPECT_EQ(driver_.total_dropped_steps(), expected_dropped);
  EXPECT_GT(expected_dropped, 100u * 590u);
  EXPECT_TRUE(all_finite(world_.bodies()));
}

TEST_F(SpiralOfDeath, AJumpOfAYearIsCountedWithoutOverflow) {
  const nanoseconds year = std::chrono::hours(24 * 365);
  clock_.advance(year);
  const FrameResult result = frame();
  EXPECT_EQ(result.steps, 6);
  EXPECT_EQ(result.dropped_steps, static_cast<std::uint64_t>(year / driver_.period()) - 6);
  real_time_frames(10);
}

}  // namespace
}  // namespace phys::testing
