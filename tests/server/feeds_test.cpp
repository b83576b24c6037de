// The snapshot feeds: flow control by acknowledgement, views shared and left, full
// states on join and on request, and the bounds on what a client can make the
// server hold.
#include <gtest/gtest.h>

#include "feed_run.h"
#include "test_scene.h"

namespace server_test {
namespace {

// In lockstep every due tick sends a snapshot (the clients answer each with an
// input), so the counts below are exact.
TEST(Feeds, AClientThatDoesNotAcknowledgeGetsItsWindowThenSkipsTicks) {
  FeedRun run(scene_file("moving-1000"), /*lockstep=*/true);
  wire::ViewSettings settings;
  settings.window = 5;
  FakeClient& c = run.join(settings);
  c.acks = false;
  run.ticks(60);
  EXPECT_EQ(c.snapshots, 5u);
  EXPECT_EQ(run.feeds().unacknowledged(1), 5u);
  EXPECT_EQ(run.feeds().stats().skipped, 55u);
  // It reads again: acknowledging all it has opens the window, and it gets the
  // newest tick, built on what it holds.
  EXPECT_EQ(run.feeds().ack(1, c.last_tick), server::AckResult::Accepted);
  run.tick();
  EXPECT_EQ(c.snapshots, 6u);
  EXPECT_EQ(c.last_tick, run.frame().tick);
  EXPECT_TRUE(run.holds_mirror(c));
  const auto [position, velocity] = run.worst_error(c);
  EXPECT_LE(position, settings.position_tolerance);
  EXPECT_LE(velocity, settings.velocity_tolerance);
}

TEST(Feeds, AnAckForATickNeverSentIsRefused) {
  FeedRun run(scene::default_scene());
  run.join({});
  EXPECT_EQ(run.feeds().ack(1, 1), server::AckResult::NeverSent);  // nothing sent yet
  run.tick();
  EXPECT_EQ(run.feeds().ack(1, run.frame().tick + 1), server::AckResult::NeverSent);
  EXPECT_EQ(run.feeds().ack(1, run.frame().tick), server::AckResult::Accepted);
  EXPECT_EQ(run.feeds().ack(1, 0), server::AckResult::Accepted);  // old: harmless
  EXPECT_EQ(run.feeds().ack(99, 1), server::AckResult::NeverSent);
}

TEST(Feeds, ClientsWithEqualSettingsShareOneViewUntilOneFallsBehind) {
  FeedRun run(scene_file("moving-1000"), /*lockstep=*/true);
  FakeClient& a = run.join({});
  run.tick();
  FakeClient& b = run.join({});  // joins the view of a, with a full state of its mirror
  run.tick();
  EXPECT_EQ(run.feeds().view_count(), 1u);
  EXPECT_EQ(run.feeds().view_members(1), 2u);
  EXPECT_TRUE(run.holds_mirror(a));
  EXPECT_TRUE(run.holds_mirror(b));
  const std::uint64_t updates = run.feeds().stats().views_updated;
  run.ticks(10);
  EXPECT_EQ(run.feeds().stats().views_updated - updates, 10u);  // one encoding a tick
  b.acks = false;
  run.ticks(30);  // b's window (12) fills: it goes on in a view of its own
  EXPECT_EQ(run.feeds().view_count(), 2u);
  EXPECT_EQ(run.feeds().stats().detached, 1u);
  EXPECT_EQ(run.feeds().ack(2, b.last_tick), server::AckResult::Accepted);
  b.acks = true;
  run.ticks(30);
  EXPECT_TRUE(run.holds_mirror(a));
  EXPECT_TRUE(run.holds_mirror(b));
  // Asking for a full state takes it back into the shared view.
  EXPECT_EQ(run.feeds().request_full_state(2), server::FullStateResult::Accepted);
  run.tick();
  EXPECT_EQ(run.feeds().view_count(), 1u);
  EXPECT_TRUE(run.holds_mirror(b));
}

TEST(Feeds, AFullStateIsSentOnJoinAndOnRequestAndRequestsWhilePendingMerge) {
  FeedRun run(scene::default_scene());
  FakeClient& c = run.join({});
  c.keep_log = true;
  run.tick();
  ASSERT_EQ(c.log.size(), 1u);
  EXPECT_TRUE(c.log[0].full());
  run.ticks(5);
  EXPECT_EQ(run.feeds().request_full_state(1), server::FullStateResult::Accepted);
  EXPECT_EQ(run.feeds().request_full_state(1), server::FullStateResult::AlreadyPending);
  c.log.clear();
  run.tick();
  ASSERT_EQ(c.log.size(), 1u);
  EXPECT_TRUE(c.log[0].full());
  EXPECT_TRUE(run.holds_mirror(c));
  // One request a tick: each is served or merged, never piled up.
  std::uint64_t full = 0;
  for (int i = 0; i < 60; ++i) {
    run.feeds().request_full_state(1);
    c.log.clear();
    run.tick();
    for (const auto& s : c.log) full += s.full() ? 1 : 0;
  }
  EXPECT_EQ(full, 60u);
  EXPECT_TRUE(run.holds_mirror(c));
}

// Other peers joining and leaving while a client reads nothing: what it is owed
// stays bounded by the bodies that exist, and it is never dropped for it.
TEST(Feeds, ChurnOfOtherPeersWhileAClientStallsIsBoundedByTheWorld) {
  FeedRun run(scene::default_scene());
  FakeClient& stalled = run.join({});
  stalled.acks = false;
  run.tick();
  for (int i = 0; i < 60; ++i) {
    FakeClient& peer = run.join({});
    run.tick();
    run.leave(peer.id);
    run.tick();
  }
  // Joined and left while it was stalled: neither announced nor removed.
  stalled.acks = true;
  stalled.keep_log = true;
  EXPECT_EQ(run.feeds().ack(1, stalled.last_tick), server::AckResult::Accepted);
  run.tick();
  ASSERT_EQ(stalled.log.size(), 1u);
  EXPECT_LE(stalled.log[0].added_size(), 13);
  EXPECT_LE(stalled.log[0].removed_size(), 13);
  EXPECT_TRUE(run.holds_mirror(stalled));
}

TEST(Feeds, EverySnapshotIntervalSendsOnlyOnItsTicks) {
  FeedRun run(scene_file("moving-1000"), /*lockstep=*/true);
  wire::ViewSettings settings;
  settings.snapshot_interval = 3;
  FakeClient& c = run.join(settings);
  c.keep_log = true;
  run.ticks(60);
  EXPECT_EQ(c.log.size(), 20u);
  for (const auto& s : c.log) EXPECT_EQ(s.tick() % 3, 0u);
  EXPECT_TRUE(run.holds_mirror(c));
}

}  // namespace
}  // namespace server_test
