// The link conditioner's schedule without sockets: explicit read times in, due times
// out. The draws are fixed by the seed on every platform; latency, jitter, bandwidth
// and stalls each move a chunk exactly as docs/NETSIM.md says.
#include "delivery_schedule.h"

#include <gtest/gtest.h>

#include <set>

#include "path_random.h"
#include "stall_timeline.h"

namespace physics_testing {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

const Clock::time_point kStart{1000s};  // a connection's start, any instant

DeliverySchedule schedule_for(const PathDirection& direction, const PathStalls& stalls = {},
                              std::uint64_t seed = 1) {
  return DeliverySchedule(direction, StallTimeline(stalls, true, kStart, PathRandom(seed + 100)),
                          PathRandom(seed));
}

TEST(PathRandom, GivesTheSameNumbersOnEveryPlatform) {
  // xoshiro256** seeded by splitmix64, as its authors give them (checked against an
  // independent implementation).
  PathRandom one(1);
  EXPECT_EQ(one.next(), 0xb3f2af6d0fc710c5ULL);
  EXPECT_EQ(one.next(), 0x853b559647364ceaULL);
  EXPECT_EQ(one.next(), 0x92f89756082a4514ULL);
  PathRandom zero(0);
  EXPECT_EQ(zero.next(), 0x99ec5f36cb75f2b4ULL);
}

TEST(PathRandom, UniformUpToCoversEveryValueAndNoMore) {
  PathRandom random(7);
  std::set<std::uint64_t> seen;
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t value = random.uniform_up_to(4);
    ASSERT_LE(value, 4u);
    seen.insert(value);
  }
  EXPECT_EQ(seen.size(), 5u);
  EXPECT_EQ(random.uniform_up_to(0), 0u);
}

TEST(PathRandom, ExponentialHasTheMeanOfItsRate) {
  PathRandom random(9);
  double sum = 0.0;
  constexpr int kDraws = 100000;
  for (int i = 0; i < kDraws; ++i) {
    const double gap = random.exponential(4.0);
    ASSERT_GE(gap, 0.0);
    sum += gap;
  }
  // Mean 0.25, standard error 0.25 / sqrt(1e5) ~ 0.0008: 0.005 is six of them.
  EXPECT_NEAR(sum / kDraws, 0.25, 0.005);
}

TEST(DeliverySchedule, LatencyDelaysEachChunkByExactlyIt) {
  DeliverySchedule schedule = schedule_for({.latency = 50ms});
  EXPECT_EQ(schedule.schedule(kStart + 10ms, 100).at, kStart + 60ms);
  EXPECT_EQ(schedule.schedule(kStart + 11ms, 100).at, kStart + 61ms);
}

TEST(DeliverySchedule, JitterStaysInItsRangeNeverReordersAndRepeatsWithTheSeed) {
  const PathDirection path{.latency = 20ms, .jitter = 10ms};
  DeliverySchedule schedule = schedule_for(path, {}, 5);
  DeliverySchedule again = schedule_for(path, {}, 5);
  DeliverySchedule other_seed = schedule_for(path, {}, 6);
  Clock::time_point previous{};
  bool differs = false;
  Clock::duration longest{0};
  for (int i = 0; i < 200; ++i) {
    const Clock::time_point read_at = kStart + i * 1ms;
    const Clock::time_point due = schedule.schedule(read_at, 10).at;
    EXPECT_GE(due, read_at + 20ms);
    EXPECT_GE(due, previous) << "chunk " << i << " before the one ahead of it";
    // Only the order may push a chunk beyond latency + jitter, to its predecessor's time.
    if (due > read_at + 30ms) {
      EXPECT_EQ(due, previous) << "chunk " << i;
    }
    EXPECT_EQ(again.schedule(read_at, 10).at, due) << "the same seed, another time";
    differs = differs || other_seed.schedule(read_at, 10).at != due;
    longest = std::max(longest, due - read_at);
    previous = due;
  }
  EXPECT_TRUE(differs);
  EXPECT_GE(longest, 25ms);
}

TEST(DeliverySchedule, ABandwidthCapSendsChunksOneAfterAnother) {
  DeliverySchedule schedule = schedule_for({.latency = 5ms, .bandwidth_bytes_per_second = 1000.0});
  // 100 bytes at 1000 B/s: 100 ms on the wire, then the latency.
  EXPECT_EQ(schedule.schedule(kStart, 100).at, kStart + 105ms);
  // Read while the link still sends the first: it waits for the link.
  EXPECT_EQ(schedule.schedule(kStart + 50ms, 100).at, kStart + 205ms);
  // Read once the link is idle: from its read time.
  EXPECT_EQ(schedule.schedule(kStart + 1s, 50).at, kStart + 1s + 55ms);
}

TEST(DeliverySchedule, AStallHoldsWhatIsDueInItToItsEnd) {
  PathStalls stalls;
  stalls.duration = 200ms;
  stalls.at = {1s, 3s};
  DeliverySchedule schedule = schedule_for({.latency = 10ms}, stalls);
  auto due = schedule.schedule(kStart + 500ms, 10);
  EXPECT_EQ(due.at, kStart + 510ms);
  EXPECT_EQ(due.stalls_begun, 0u);
  // Due at 1.05 s, in the stall of [1 s, 1.2 s).
  due = schedule.schedule(kStart + 1040ms, 10);
  EXPECT_EQ(due.at, kStart + 1200ms);
  EXPECT_EQ(due.stalls_begun, 1u);
  EXPECT_EQ(schedule.schedule(kStart + 1100ms, 10).at, kStart + 1200ms);
  EXPECT_EQ(schedule.schedule(kStart + 1195ms, 10).at, kStart + 1205ms);
  // A chunk read after the second stall ended passes it, unheld.
  due = schedule.schedule(kStart + 4s, 10);
  EXPECT_EQ(due.at, kStart + 4010ms);
  EXPECT_EQ(due.stalls_begun, 1u);
}

TEST(DeliverySchedule, PeriodicStallsBeginAtEachMultipleOfTheirPeriod) {
  PathStalls stalls;
  stalls.duration = 100ms;
  stalls.every = 1s;
  DeliverySchedule schedule = schedule_for({}, stalls);
  EXPECT_EQ(schedule.schedule(kStart + 999ms, 1).at, kStart + 999ms);
  EXPECT_EQ(schedule.schedule(kStart + 1s, 1).at, kStart + 1100ms);
  EXPECT_EQ(schedule.schedule(kStart + 2050ms, 1).at, kStart + 2100ms);
  EXPECT_EQ(schedule.schedule(kStart + 2100ms, 1).at, kStart + 2100ms);
}

TEST(StallTimeline, RandomStallsComeAtTheirRateAndRepeatWithTheSeed) {
  PathStalls stalls;
  stalls.duration = 10ms;
  stalls.per_second = 2.0;
  StallTimeline timeline(stalls, true, kStart, PathRandom(3));
  StallTimeline again(stalls, true, kStart, PathRandom(3));
  std::uint64_t begun = 0;
  // One probe a millisecond for 500 s: every stall is passed.
  for (int i = 0; i < 500000; ++i) {
    const Clock::time_point due = kStart + i * 1ms;
    const auto release = timeline.release(due);
    EXPECT_EQ(again.release(due).at, release.at);
    begun += release.stalls_begun;
  }
  // 1000 expected; Poisson, standard deviation ~32: 150 is almost five of them.
  EXPECT_NEAR(static_cast<double>(begun), 1000.0, 150.0);
}

TEST(StallTimeline, AResetTakesTheNewStallsFromItsTimeOn) {
  PathStalls stalls;
  stalls.duration = 100ms;
  stalls.at = {1s};
  StallTimeline timeline(stalls, true, kStart, PathRandom(1));
  stalls.at = {500ms, 2s};
  timeline.reset(stalls, true, kStart + 800ms);
  // The stall at 0.5 s is in the past of the reset; the one at 1 s is gone.
  EXPECT_EQ(timeline.release(kStart + 1050ms).at, kStart + 1050ms);
  EXPECT_EQ(timeline.release(kStart + 2050ms).at, kStart + 2100ms);
  // Not applying to this direction: nothing stalls.
  timeline.reset(stalls, false, kStart);
  EXPECT_EQ(timeline.release(kStart + 2050ms).at, kStart + 2050ms);
}

}  // namespace
}  // namespace physics_testing
