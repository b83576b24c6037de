// The playout buffer with a fake clock: snapshots of known trajectories arrive with
// scripted jitter, loss and stalls; frames are taken at a display's rate and must
// follow the trajectories smoothly, with the lag the buffer states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "client/playout_buffer.h"
#include "playout_test_support.h"

namespace {

using namespace playout_test;

// A fixed sequence in [0, 1): the scripted jitter, the same on every run.
class Script {
 public:
  double next() {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

 private:
  std::uint64_t state_ = 12345;
};

// Drives a buffer: each tick's snapshot arrives at its server time plus the latency
// plus `jitter(tick)` (or never, when `lost(tick)`); frames are taken every kFrame.
struct ScriptedRun {
  PlayoutBuffer buffer{PlayoutSettings{}};
  std::vector<PlayoutFrame> frames;
  std::vector<double> frame_times;
  std::vector<double> delays;
  std::vector<double> offsets;

  template <class Jitter, class Lost>
  void play(double seconds, Jitter jitter, Lost lost) {
    struct Arrival {
      double at;
      std::uint64_t tick;
    };
    std::vector<Arrival> arrivals;
    const auto ticks = static_cast<std::uint64_t>(seconds * kTickRate);
    for (std::uint64_t tick = 1; tick <= ticks; ++tick) {
      if (lost(tick)) continue;
      arrivals.push_back({static_cast<double>(tick) / kTickRate + kLatency + jitter(tick), tick});
    }
    // TCP keeps the order: a snapshot is never read before the one sent before it.
    for (std::size_t i = 1; i < arrivals.size(); ++i)
      arrivals[i].at = std::max(arrivals[i].at, arrivals[i - 1].at);
    std::size_t next = 0;
    for (double now = 0.0; now < seconds; now += kFrame) {
      while (next < arrivals.size() && arrivals[next].at <= now) {
        const PushResult result = buffer.push(snapshot_at(arrivals[next].tick), arrivals[next].at);
        ASSERT_EQ(result, PushResult::Accepted);
        ++next;
      }
      frames.push_back(buffer.state_at(now));
      frame_times.push_back(now);
      delays.push_back(buffer.delay());
      offsets.push_back(buffer.offset());
    }
  }
};

TEST(PlayoutBuffer, SmoothUnderJitterWithTheLagItStates) {
  ScriptedRun run;
  Script script;
  // Up to 30 ms of jitter on a 50 ms link, at 60 Hz.
  run.play(
      10.0, [&](std::uint64_t) { return 0.030 * script.next(); },
      [](std::uint64_t) { return false; });
  const double slew = run.buffer.settings().slew;
  const double circle_speed = kRadius * kOmega;
  const double linear_speed = std::hypot(kVelocity.x, kVelocity.y);
  std::size_t checked = 0;
  double worst = 0.0;  // the largest |lag - delay|
  for (std::size_t i = 1; i < run.frames.size(); ++i) {
    if (run.frame_times[i] < 2.0) continue;  // the delay settles in the first seconds
    const PlayoutFrame& frame = run.frames[i];
    const PlayoutFrame& before = run.frames[i - 1];
    ASSERT_EQ(frame.status, PlayoutStatus::Interpolating) << "at " << run.frame_times[i];
    // Continuity: no body moves further in one frame than its speed allows at the
    // fastest the shown time may run (1 + slew).
    const double bound = (1.0 + slew) * kFrame;
    EXPECT_LE(distance(body(frame, kLinear)->position, body(before, kLinear)->position),
              bound * linear_speed + 1e-12);
    EXPECT_LE(distance(body(frame, kCircle)->position, body(before, kCircle)->position),
              bound * circle_speed + 1e-12);
    EXPECT_EQ(body(frame, kResting)->position, (client::Vec2{5.0, 0.5}));
    // The lag is what the buffer says: the true one (the newest server time now,
    // now - the fastest transit, minus the shown time) is the frame's lag, up to the
    // buffer's estimate of the fastest transit (the fastest among 64 snapshots).
    const double true_lag = (run.frame_times[i] - kLatency) - frame.server_time;
    EXPECT_GE(run.offsets[i], kLatency - 1e-12);
    EXPECT_NEAR(true_lag, frame.lag + (run.offsets[i] - kLatency), 1e-9);
    EXPECT_LT(run.offsets[i] - kLatency, 0.003);
    // And the lag follows the delay: its distance to the delay grows only by what
    // the delay and offset moved, and shrinks by the slew each frame.
    const double error = std::abs(frame.lag - run.delays[i]);
    const double error_before = std::abs(before.lag - run.delays[i - 1]);
    const double moved =
        std::abs((run.delays[i] - run.delays[i - 1]) + (run.offsets[i] - run.offsets[i - 1]));
    EXPECT_LE(error, std::max(0.0, error_before + moved - slew * kFrame) + 1e-12);
    worst = std::max(worst, error);
    // And the bodies are where they were at the shown server time: the linear one
    // exactly (up to rounding), the circle within its chord's sagitta.
    EXPECT_NEAR(distance(body(frame, kLinear)->position, linear_at(frame.server_time)), 0.0, 1e-9);
    const double t = frame.server_time;
    const double sagitta = kRadius * (1.0 - std::cos(kOmega / kTickRate / 2.0));
    EXPECT_LE(distance(body(frame, kCircle)->position,
                       {kRadius * std::cos(kOmega * t), kRadius * std::sin(kOmega * t)}),
              sagitta + 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
  // Here the shown lag stays within 5 ms of the delay (the jitter estimate moves the
  // delay by up to 3 x 30 ms / 16 = 5.6 ms a snapshot; the slew follows at 10%).
  EXPECT_LT(worst, 0.005);
  // About three intervals plus the jitter measured: 50 ms of intervals, and the 30 ms
  // spread of the jitter shows as some tens of ms more.
  EXPECT_GT(run.buffer.delay(), 3.0 / kTickRate + 0.005);
  EXPECT_LT(run.buffer.delay(), 3.0 / kTickRate + 0.060);
  EXPECT_GT(run.buffer.jitter(), 0.0);
}

TEST(PlayoutBuffer, WithoutJitterTheDelayIsThreeIntervals) {
  ScriptedRun run;
  run.play(
      3.0, [](std::uint64_t) { return 0.0; }, [](std::uint64_t) { return false; });
  EXPECT_NEAR(run.buffer.delay(), 3.0 / kTickRate, 1e-9);
  EXPECT_NEAR(run.buffer.offset(), kLatency, 1e-9);
  EXPECT_NEAR(run.frames.back().lag, 3.0 / kTickRate, 1e-9);
}

TEST(PlayoutBuffer, ALostSecondIsBridgedThenRecovered) {
  ScriptedRun run;
  // Snapshots of server times [3 s, 4 s) never arrive (the server skipped them).
  run.play(
      8.0, [](std::uint64_t) { return 0.0; },
      [](std::uint64_t tick) { return tick >= 180 && tick < 240; });
  const double max_extrapolation = run.buffer.settings().max_extrapolation;
  const client::Vec2 last_before = linear_at(179.0 / kTickRate);
  bool extrapolated = false;
  bool held = false;
  double recovered_at = -1.0;
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    const PlayoutFrame& frame = run.frames[i];
    const double now = run.frame_times[i];
    if (now < 1.0) continue;
    ASSERT_EQ(frame.bodies.size(), 3u) << "at " << now;
    const client::PlayoutBody& linear = *body(frame, kLinear);
    ASSERT_TRUE(std::isfinite(linear.position.x) && std::isfinite(linear.position.y));
    if (frame.status == PlayoutStatus::Extrapolating) extrapolated = true;
    if (frame.status == PlayoutStatus::Holding) {
      held = true;
      // Held where the extrapolation limit put it, never further.
      EXPECT_NEAR(distance(linear.position, last_before),
                  std::hypot(kVelocity.x, kVelocity.y) * max_extrapolation, 1e-9);
    }
    if (frame.status == PlayoutStatus::Extrapolating || frame.status == PlayoutStatus::Holding) {
      EXPECT_LE(frame.extrapolated, 1.0 + 1e-9);
    }
    if (now > 4.1 && recovered_at < 0.0 && frame.status == PlayoutStatus::Interpolating)
      recovered_at = now;
    if (recovered_at > 0.0 && now > recovered_at) {
      EXPECT_EQ(frame.status, PlayoutStatus::Interpolating) << "at " << now;
      EXPECT_NEAR(distance(linear.position, linear_at(frame.server_time)), 0.0, 1e-9);
      EXPECT_NEAR(frame.lag, run.delays[i], 1e-9);
    }
  }
  EXPECT_TRUE(extrapolated);
  EXPECT_TRUE(held);
  // Interpolating again as soon as the first snapshot after the loss is a delay old.
  ASSERT_GT(recovered_at, 0.0);
  EXPECT_LT(recovered_at, 4.0 + kLatency + 3.0 / kTickRate + 0.02);
  EXPECT_EQ(run.buffer.stats().resets, 0u);
  EXPECT_EQ(run.buffer.stats().snaps, 0u);
}

TEST(PlayoutBuffer, ASecondStalledAndDeliveredAtOnceIsBridgedThenRecovered) {
  ScriptedRun run;
  // A stalled link: the snapshots of [3 s, 4 s) wait and arrive with the one of 4 s.
  run.play(
      10.0,
      [](std::uint64_t tick) {
        return tick >= 180 && tick < 240 ? (240.0 - static_cast<double>(tick)) / kTickRate : 0.0;
      },
      [](std::uint64_t) { return false; });
  double jitter_peak = 0.0;
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    const PlayoutFrame& frame = run.frames[i];
    const double now = run.frame_times[i];
    if (now < 1.0) continue;
    ASSERT_EQ(frame.bodies.size(), 3u);
    jitter_peak = std::max(jitter_peak, run.delays[i]);
    if (now > 3.2 && now < 4.0) {
      EXPECT_NE(frame.status, PlayoutStatus::Interpolating);
    }
    if (now > 4.0 && i > 0) {
      // The shown time keeps running at the clock's rate (within the slew): the late
      // burst does not make it jump back or forward.
      const double moved = frame.server_time - run.frames[i - 1].server_time;
      EXPECT_GE(moved, (1.0 - run.buffer.settings().slew) * kFrame - 1e-12);
      EXPECT_LE(moved, (1.0 + run.buffer.settings().slew) * kFrame + 1e-12);
    }
    if (now > 6.0) {
      EXPECT_EQ(frame.status, PlayoutStatus::Interpolating) << "at " << now;
      EXPECT_NEAR(distance(body(frame, kLinear)->position, linear_at(frame.server_time)), 0.0,
                  1e-9);
    }
  }
  // The stall showed as jitter, and the delay grew, then came back down.
  EXPECT_GT(jitter_peak, 3.0 / kTickRate + 0.05);
  EXPECT_LT(run.delays.back(), 3.0 / kTickRate + 0.001);
}

TEST(PlayoutBuffer, AGapBetweenSnapshotsIsCarriedAtTheEarlierVelocity) {
  PlayoutSettings settings;
  settings.send_intervals = 0.0;  // show the newest server time: no delay
  PlayoutBuffer buffer(settings);
  // A heartbeat a second apart: at rest at tick 60, moving by tick 120.
  client::Snapshot rest;
  rest.tick = 60;
  rest.bodies.push_back({7, {0.0, 0.0}, {0.0, 0.0}});
  client::Snapshot moving = rest;
  moving.tick = 120;
  moving.bodies[0] = {7, {0.1, 0.0}, {6.0, 0.0}};
  ASSERT_EQ(buffer.push(rest, 1.0), PushResult::Accepted);
  ASSERT_EQ(buffer.push(moving, 2.0), PushResult::Accepted);
  // offset = 0 (transit 0 for both): the shown time is the clock's.
  for (double now = 1.0; now < 2.0 - 1.0 / kTickRate; now += 0.01) {
    const PlayoutFrame& frame = buffer.state_at(now);
    ASSERT_EQ(frame.status, PlayoutStatus::Interpolating);
    EXPECT_EQ(frame.bodies[0].position, (client::Vec2{0.0, 0.0})) << "at " << now;
  }
  const PlayoutFrame& end = buffer.state_at(2.0);
  EXPECT_NEAR(end.bodies[0].position.x, 0.1, 1e-12);
}

}  // namespace
