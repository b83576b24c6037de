// The playout buffer against bad input: NaN or infinite times and states, stale and
// duplicate ticks, a render clock going back, a huge tick gap, more snapshots than
// it holds, settings out of range. Each is refused or absorbed, and it keeps serving.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "client/playout_buffer.h"
#include "playout_test_support.h"

namespace {

using namespace playout_test;

TEST(PlayoutBuffer, RefusesBadSnapshotsAndKeepsServing) {
  PlayoutBuffer buffer(PlayoutSettings{});
  EXPECT_EQ(buffer.state_at(0.0).status, PlayoutStatus::Empty);
  EXPECT_TRUE(buffer.state_at(0.0).bodies.empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(buffer.push(snapshot_at(10), nan), PushResult::BadTime);
  EXPECT_EQ(buffer.push(snapshot_at(10), inf), PushResult::BadTime);
  client::Snapshot broken = snapshot_at(10);
  broken.bodies[1].position.x = nan;
  EXPECT_EQ(buffer.push(broken, 1.0), PushResult::BadState);
  broken = snapshot_at(10);
  broken.bodies[0].velocity.y = -inf;
  EXPECT_EQ(buffer.push(broken, 1.0), PushResult::BadState);
  EXPECT_EQ(buffer.size(), 0u);

  ASSERT_EQ(buffer.push(snapshot_at(10), 1.0), PushResult::Accepted);
  EXPECT_EQ(buffer.push(snapshot_at(10), 1.1), PushResult::Stale);  // duplicate tick
  EXPECT_EQ(buffer.push(snapshot_at(9), 1.1), PushResult::Stale);   // older tick
  EXPECT_EQ(buffer.size(), 1u);
  // An arrival before the previous one is taken as the previous one.
  ASSERT_EQ(buffer.push(snapshot_at(11), 0.5), PushResult::Accepted);
  EXPECT_EQ(buffer.stats().clock_backwards, 1u);
  EXPECT_NEAR(buffer.offset(), 1.0 - 11.0 / kTickRate, 1e-12);
  const auto& stats = buffer.stats();
  EXPECT_EQ(stats.bad_time, 2u);
  EXPECT_EQ(stats.bad_state, 2u);
  EXPECT_EQ(stats.stale, 2u);
  EXPECT_EQ(stats.accepted, 2u);
}

TEST(PlayoutBuffer, RenderTimeGoingBackOrNaNNeverMovesTheShownTimeBack) {
  PlayoutBuffer buffer(PlayoutSettings{});
  for (std::uint64_t tick = 1; tick <= 120; ++tick)
    ASSERT_EQ(buffer.push(snapshot_at(tick), static_cast<double>(tick) / kTickRate + kLatency),
              PushResult::Accepted);
  const double shown = buffer.state_at(1.5).server_time;
  EXPECT_EQ(buffer.state_at(1.0).server_time, shown);
  EXPECT_EQ(buffer.state_at(std::numeric_limits<double>::quiet_NaN()).server_time, shown);
  EXPECT_EQ(buffer.state_at(-std::numeric_limits<double>::infinity()).server_time, shown);
  EXPECT_EQ(buffer.stats().clock_backwards, 3u);
  EXPECT_GT(buffer.state_at(1.51).server_time, shown);
}

TEST(PlayoutBuffer, AHugeGapStartsAgainFromTheNewSnapshot) {
  PlayoutBuffer buffer(PlayoutSettings{});
  for (std::uint64_t tick = 1; tick <= 30; ++tick)
    ASSERT_EQ(buffer.push(snapshot_at(tick), static_cast<double>(tick) / kTickRate + kLatency),
              PushResult::Accepted);
  (void)buffer.state_at(0.6);
  // A tick 2^40 later (a server restarted or a corrupt tick).
  const std::uint64_t far = (1ull << 40);
  EXPECT_EQ(buffer.push(snapshot_at(far), 0.7), PushResult::Reset);
  EXPECT_EQ(buffer.size(), 1u);
  EXPECT_EQ(buffer.stats().resets, 1u);
  EXPECT_EQ(buffer.jitter(), 0.0);
  const PlayoutFrame& frame = buffer.state_at(0.71);
  EXPECT_EQ(frame.newest_tick, far);
  EXPECT_EQ(frame.bodies.size(), 3u);
  EXPECT_NEAR(frame.lag, buffer.delay(), 1e-6);
}

TEST(PlayoutBuffer, HoldsAtMostItsCapacity) {
  PlayoutSettings settings;
  settings.capacity = 16;
  PlayoutBuffer buffer(settings);
  for (std::uint64_t tick = 1; tick <= 1000; ++tick)
    ASSERT_EQ(buffer.push(snapshot_at(tick), static_cast<double>(tick) / kTickRate),
              PushResult::Accepted);
  EXPECT_EQ(buffer.size(), 16u);
  EXPECT_EQ(buffer.stats().dropped, 1000u - 16u);
  EXPECT_EQ(buffer.newest()->tick, 1000u);
}

TEST(PlayoutBuffer, SettingsOutOfRangeAreRefusedWithTheirName) {
  PlayoutSettings settings;
  settings.tick_rate = 0.0;
  EXPECT_NE(settings.validate().find("tick_rate"), std::string::npos);
  EXPECT_THROW(PlayoutBuffer{settings}, std::invalid_argument);
  settings = PlayoutSettings{};
  settings.capacity = 1;
  EXPECT_NE(settings.validate().find("capacity"), std::string::npos);
  settings = PlayoutSettings{};
  settings.max_delay = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(settings.validate().find("max_delay"), std::string::npos);
  settings = PlayoutSettings{};
  settings.slew = 2.0;
  EXPECT_NE(settings.validate().find("slew"), std::string::npos);
  EXPECT_TRUE(PlayoutSettings{}.validate().empty());
}

}  // namespace
