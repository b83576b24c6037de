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

// A body that takes a freed slot gets the slot's next generation, so its id is larger
// than those of bodies in later slots: the world's index order is then not id order.
// Records are sent as ascending id gaps, so a client holding both bodies must still
// be sent them in id order, and every snapshot must apply.
TEST(Feeds, ABodyInAReusedSlotIsSentInIdOrder) {
  FeedRun run(scene::default_scene());
  FakeClient& watcher = run.join({});
  FakeClient& first = run.join({});
  const server::FeedClient first_id = first.id;
  FakeClient& second = run.join({});
  const server::FeedClient second_id = second.id;
  run.ticks(3);
  run.leave(first_id);
  run.tick();
  FakeClient& reused = run.join({});
  const server::FeedClient reused_id = reused.id;
  for (int i = 0; i < 30; ++i) {
    const std::uint64_t next = run.sim().current_tick() + 1;
    run.sim().submit_input(second_id, next, {3.0 * ((i % 4) - 1.5), 2.0});
    run.sim().submit_input(reused_id, next, {-3.0 * ((i % 4) - 1.5), 2.0});
    run.tick();
  }
  const auto& bodies = run.frame().bodies;
  for (std::size_t i = 1; i < bodies.size(); ++i) EXPECT_LT(bodies[i - 1].id, bodies[i].id);
  // The slot really was reused out of order (otherwise this test proves nothing).
  const auto second_body = run.sim().body_of(second_id);
  const auto reused_body = run.sim().body_of(reused_id);
  ASSERT_TRUE(second_body.has_value());
  ASSERT_TRUE(reused_body.has_value());
  EXPECT_LT(reused_body->index, second_body->index);
  EXPECT_GT(reused_body->packed(), second_body->packed());
  EXPECT_GT(watcher.records, 0u);
  EXPECT_TRUE(run.holds_mirror(watcher));
  EXPECT_TRUE(run.holds_mirror(run.client(second_id)));
  EXPECT_TRUE(run.holds_mirror(run.client(reused_id)));
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
