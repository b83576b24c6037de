// The input clock, driven by hand: the server's tick it estimates from snapshots, the
// tick it has inputs sent for, and the lead it adapts from the margins the server
// reports (client/include/client/input_clock.h).
#include "client/input_clock.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace std::chrono_literals;
using client::InputClock;
using client::InputClockConfig;
using time_point = InputClock::time_point;

constexpr double kRate = 60.0;

InputClockConfig at_60hz(std::chrono::microseconds safety = std::chrono::microseconds(2000)) {
  InputClockConfig config;
  config.tick_rate = kRate;
  config.safety = safety;
  return config;
}
const std::chrono::nanoseconds kPeriod = std::chrono::duration_cast<std::chrono::nanoseconds>(
    std::chrono::duration<double>(1.0 / kRate));

// A server stepping tick t at origin + t periods; snapshots reach the client
// `one_way` later.
struct Path {
  time_point origin = time_point{} + 1000s;
  std::chrono::nanoseconds one_way = 50ms;
  time_point stepped(std::uint64_t tick) const { return origin + kPeriod * tick; }
  time_point seen(std::uint64_t tick) const { return stepped(tick) + one_way; }
};

TEST(InputClock, EstimatesTheServersTickFromSnapshotsAndTheRoundTrip) {
  InputClock clock(at_60hz());
  Path path;
  clock.on_round_trip(2 * path.one_way, path.seen(0));
  for (std::uint64_t t = 1; t <= 30; ++t) clock.on_tick_seen(t, path.seen(t));
  // At the moment tick 40 is stepped the estimate is 40, to a small fraction.
  EXPECT_NEAR(clock.server_tick(path.stepped(40)), 40.0, 1e-6);
  // Jitter only delays snapshots: a late one moves the estimate a sixteenth of its
  // delay, and the next one on time puts it back.
  clock.on_tick_seen(31, path.seen(31) + 12ms);
  const double tick_ms = 1000.0 / kRate;
  EXPECT_NEAR(clock.server_tick(path.stepped(40)), 40.0 - 0.75 / tick_ms, 1e-6);
  clock.on_tick_seen(32, path.seen(32));
  EXPECT_NEAR(clock.server_tick(path.stepped(40)), 40.0, 1e-6);
  // A server that fell 50 ms behind is followed: most of the way in 48 snapshots.
  path.origin += 50ms;
  for (std::uint64_t t = 33; t <= 80; ++t) clock.on_tick_seen(t, path.seen(t));
  EXPECT_NEAR(clock.server_tick(path.stepped(90)), 90.0, 0.2);
}

TEST(InputClock, FirstLeadIsHalfTheRoundTripPlusTheSafety) {
  InputClock clock(at_60hz(2000us));
  Path path;
  clock.on_round_trip(100ms, path.seen(0));
  EXPECT_EQ(clock.lead(), 52ms);
  EXPECT_EQ(clock.delay(), 4u);  // 52 ms is 3.12 ticks, rounded up
  for (std::uint64_t t = 1; t <= 10; ++t) clock.on_tick_seen(t, path.seen(t));
  // At the time tick 20 steps the client sends up to 20 + 3.12 ticks.
  EXPECT_EQ(clock.send_up_to(path.stepped(20)), 23u);
  // The next input falls due when the estimate passes 24 - 3.12 ticks.
  const time_point next = clock.next_send_time(path.stepped(20));
  EXPECT_EQ(clock.send_up_to(next + 1us), 24u);
  EXPECT_EQ(clock.send_up_to(next - 1us), 23u);
}

TEST(InputClock, LateMarginRaisesTheLeadOnceARoundTrip) {
  InputClock clock(at_60hz(2000us));
  Path path;
  clock.on_round_trip(100ms, path.seen(0));
  const auto before = clock.lead();
  // An input 5 ms late: the lead grows by the shortfall, 7 ms.
  clock.on_margin(-5000us, path.seen(10));
  EXPECT_EQ(clock.lead(), before + 7ms);
  EXPECT_EQ(clock.raises(), 1u);
  // Margins reported within the next round trip are of inputs sent before the raise.
  clock.on_margin(-5000us, path.seen(12));
  EXPECT_EQ(clock.raises(), 1u);
  // After it, another late one raises again.
  clock.on_margin(-1000us, path.seen(10) + 100ms + 3 * kPeriod);
  EXPECT_EQ(clock.raises(), 2u);
  EXPECT_EQ(clock.lead(), before + 7ms + 3ms);
}

TEST(InputClock, SpareMarginLowersTheLeadSlowly) {
  InputClock clock(at_60hz(2000us));
  Path path;
  clock.on_round_trip(100ms, path.seen(0));
  const auto before = clock.lead();
  // Every input 22 ms early for a second: 20 ms to spare, half of it given back.
  for (std::uint64_t t = 1; t <= 61; ++t) clock.on_margin(22000us, path.seen(t));
  EXPECT_EQ(clock.lowers(), 1u);
  EXPECT_EQ(clock.lead(), before - 10ms);
  // Within an eighth of a tick (2.08 ms) of the safety: kept.
  InputClock steady(at_60hz(2000us));
  steady.on_round_trip(100ms, path.seen(0));
  for (std::uint64_t t = 1; t <= 300; ++t) steady.on_margin(4000us, path.seen(t));
  EXPECT_EQ(steady.lowers(), 0u);
  EXPECT_EQ(steady.lead(), before);
}

TEST(InputClock, FixedDelayIgnoresMargins) {
  InputClockConfig config = at_60hz();
  config.fixed_delay = 6;
  InputClock clock(config);
  Path path;
  clock.on_round_trip(100ms, path.seen(0));
  clock.on_margin(-50000us, path.seen(5));
  EXPECT_EQ(clock.delay(), 6u);
  EXPECT_EQ(clock.lead(), kPeriod * 6);
}

TEST(InputClock, LeadIsCappedAtTheLargestDelay) {
  InputClockConfig config = at_60hz();
  config.max_delay = 10;
  InputClock clock(config);
  Path path;
  clock.on_round_trip(100ms, path.seen(0));
  clock.on_margin(-10000000us, path.seen(5));  // ten seconds late
  EXPECT_EQ(clock.delay(), 10u);
}

TEST(InputClock, WaitingLockstepServerStandsStillUntilATickIsSeen) {
  InputClock clock(at_60hz());
  clock.on_waiting_at(7);
  const time_point now = time_point{} + 5s;
  EXPECT_EQ(clock.server_tick(now), 7.0);
  EXPECT_EQ(clock.server_tick(now + 10s), 7.0);
  clock.on_tick_seen(8, now);
  EXPECT_GT(clock.server_tick(now + 1s), 60.0);
}

}  // namespace
