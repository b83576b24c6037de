// Which bodies a playout frame holds: still ones marked, ones that leave kept until
// the later snapshot, new ones shown from it.
#include <gtest/gtest.h>

#include "client/playout_buffer.h"
#include "playout_test_support.h"

namespace {

using namespace playout_test;

TEST(PlayoutBuffer, StillBodiesAreTheOnesUnchangedInTheTwoNewestSnapshots) {
  PlayoutBuffer buffer(PlayoutSettings{});
  ASSERT_EQ(buffer.push(snapshot_at(1), 1.0), PushResult::Accepted);
  ASSERT_EQ(buffer.push(snapshot_at(2), 1.02), PushResult::Accepted);
  const PlayoutFrame& frame = buffer.state_at(1.5);
  EXPECT_TRUE(body(frame, kResting)->still);
  EXPECT_FALSE(body(frame, kLinear)->still);
  EXPECT_FALSE(body(frame, kCircle)->still);
}

TEST(PlayoutBuffer, BodiesThatLeaveStayUntilTheLaterSnapshotAndNewOnesAppearAtIt) {
  PlayoutSettings settings;
  settings.send_intervals = 0.0;
  PlayoutBuffer buffer(settings);
  client::Snapshot a;
  a.tick = 60;
  a.bodies = {{1, {0, 0}, {0, 0}}, {2, {1, 1}, {0, 0}}};
  client::Snapshot b;
  b.tick = 61;
  b.bodies = {{1, {0, 0}, {0, 0}}, {3, {2, 2}, {0, 0}}};
  ASSERT_EQ(buffer.push(a, 1.0), PushResult::Accepted);
  ASSERT_EQ(buffer.push(b, 1.0 + 1.0 / kTickRate), PushResult::Accepted);
  const PlayoutFrame& between = buffer.state_at(1.0 + 0.5 / kTickRate);
  ASSERT_EQ(between.bodies.size(), 2u);
  EXPECT_EQ(between.bodies[0].body_id, 1u);
  EXPECT_EQ(between.bodies[1].body_id, 2u);
  const PlayoutFrame& at_b = buffer.state_at(1.0 + 1.0 / kTickRate + 1e-6);
  ASSERT_EQ(at_b.bodies.size(), 2u);
  EXPECT_EQ(at_b.bodies[1].body_id, 3u);
}

}  // namespace
