// physics-view's playback of a client recording, without a window: pause, single
// steps, speed and seeking, on a recording built in code.
#include "replay_world.h"

#include <SDL.h>
#include <gtest/gtest.h>

#include <cmath>

namespace {

constexpr double kTickRate = 60.0;
constexpr std::uint64_t kFirst = 10;
constexpr std::uint64_t kLast = 400;
constexpr std::uint64_t kAddedAt = 200;  // body 9 appears in this tick's snapshot

// One body moving 0.1 m a tick along x, a snapshot every tick from kFirst to kLast.
client::ClientRecording recording() {
  client::ClientRecording out;
  out.welcome.tick_rate = kTickRate;
  out.welcome.current_tick = kFirst - 1;
  out.welcome.view.snapshot_interval = 1;
  client::BodyShape mover;
  mover.body_id = 1;
  mover.shape = client::ShapeType::Circle;
  mover.radius = 0.5;
  out.welcome.bodies.push_back(mover);
  for (std::uint64_t tick = kFirst; tick <= kLast; ++tick) {
    client::RecordedSnapshot recorded;
    recorded.snapshot.tick = tick;
    recorded.snapshot.state_hash = tick * 1000;
    const double x = 0.1 * static_cast<double>(tick);
    recorded.snapshot.bodies.push_back({1, {x, 0.0}, {0.1 * kTickRate, 0.0}});
    if (tick == kAddedAt) {
      client::BodyShape added = mover;
      added.body_id = 9;
      recorded.snapshot.added.push_back(added);
    }
    recorded.arrival = static_cast<double>(tick) / kTickRate + 0.05;
    out.snapshots.push_back(std::move(recorded));
  }
  return out;
}

double x_of(const client::PlayoutFrame& frame) {
  return frame.bodies.empty() ? std::nan("") : frame.bodies.front().position.x;
}

TEST(ReplayWorld, PlaysAtItsSpeedFromTheFirstSnapshot) {
  viewer::ReplayWorld replay(recording(), "test", 1.0);
  EXPECT_NEAR(x_of(replay.update(100.0)), 1.0, 1e-9);  // tick 10
  EXPECT_NEAR(x_of(replay.update(100.5)), 4.0, 1e-9);  // 30 ticks later
  EXPECT_EQ(replay.current().tick, 40u);
  replay.set_speed(2.0);
  EXPECT_NEAR(x_of(replay.update(101.0)), 10.0, 1e-9);  // 0.5 s at 2x: 60 ticks
  EXPECT_FALSE(replay.paused());
  // Past the end it stops at the last snapshot, paused.
  EXPECT_NEAR(x_of(replay.update(200.0)), 40.0, 1e-9);
  EXPECT_TRUE(replay.paused());
  EXPECT_EQ(replay.current().tick, kLast);
}

TEST(ReplayWorld, PausedItStaysAndStepsOneSnapshotAtATime) {
  viewer::ReplayWorld replay(recording(), "test", 1.0);
  replay.update(0.0);
  replay.update(0.25);  // tick 25
  replay.set_paused(true);
  EXPECT_NEAR(x_of(replay.update(10.0)), 2.5, 1e-9);
  replay.step(+1);
  EXPECT_NEAR(x_of(replay.update(11.0)), 2.6, 1e-9);
  EXPECT_EQ(replay.current().tick, 26u);
  replay.step(-1);
  replay.step(-1);
  EXPECT_NEAR(x_of(replay.update(12.0)), 2.4, 1e-9);
  EXPECT_EQ(replay.current().tick, 24u);
  // Between two snapshots, a step goes to the next one, not past it.
  replay.seek(24.5 / kTickRate);
  replay.step(+1);
  EXPECT_EQ(replay.current().tick, 25u);
  replay.seek(0.0);
  replay.step(-1);  // at the first: stays
  EXPECT_EQ(replay.current().tick, kFirst);
}

TEST(ReplayWorld, SeeksForwardAndBackWithTheShapesOfTheTimeShown) {
  viewer::ReplayWorld replay(recording(), "test", 1.0);
  replay.set_paused(true);
  replay.seek_tick(300);
  EXPECT_NEAR(x_of(replay.update(0.0)), 30.0, 1e-9);
  EXPECT_NE(replay.shapes().find(9), nullptr);
  // Back before what the playout buffer holds: played again from the Welcome.
  replay.seek_tick(100);
  EXPECT_NEAR(x_of(replay.update(0.0)), 10.0, 1e-9);
  EXPECT_EQ(replay.shapes().find(9), nullptr);
  EXPECT_EQ(replay.current().state_hash, 100u * 1000u);
  // Out of the recording: clamped to its ends; a NaN changes nothing.
  replay.seek(-5.0);
  EXPECT_EQ(replay.current().tick, kFirst);
  replay.seek(1e9);
  EXPECT_EQ(replay.current().tick, kLast);
  replay.seek(std::nan(""));
  EXPECT_EQ(replay.current().tick, kLast);
  replay.seek_tick(1u << 30);
  EXPECT_EQ(replay.current().tick, kLast);
}

TEST(ReplayWorld, KeysPauseStepChangeSpeedAndSeek) {
  viewer::ReplayWorld replay(recording(), "test", 1.0);
  replay.update(0.0);
  EXPECT_TRUE(replay.key(SDLK_SPACE));
  EXPECT_TRUE(replay.paused());
  EXPECT_TRUE(replay.key(SDLK_PERIOD));
  EXPECT_EQ(replay.current().tick, kFirst + 1);
  EXPECT_TRUE(replay.key(SDLK_COMMA));
  EXPECT_EQ(replay.current().tick, kFirst);
  EXPECT_TRUE(replay.key(SDLK_RIGHTBRACKET));
  EXPECT_DOUBLE_EQ(replay.speed(), 2.0);
  EXPECT_TRUE(replay.key(SDLK_LEFTBRACKET));
  EXPECT_TRUE(replay.key(SDLK_LEFTBRACKET));
  EXPECT_DOUBLE_EQ(replay.speed(), 0.5);
  EXPECT_TRUE(replay.key(SDLK_PAGEDOWN));
  EXPECT_EQ(replay.current().tick, kFirst + 300);
  EXPECT_TRUE(replay.key(SDLK_PAGEUP));
  EXPECT_EQ(replay.current().tick, kFirst);
  EXPECT_FALSE(replay.key(SDLK_z));  // not a playback key: the window's
  for (int i = 0; i < 20; ++i) replay.key(SDLK_RIGHTBRACKET);
  EXPECT_DOUBLE_EQ(replay.speed(), viewer::kMaxSpeed);
}

}  // namespace
