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

// An Ack of tick T frees T itself, not only the ticks before it.
TEST(Feeds, AnAckOfATickFreesThatTick) {
  FeedRun run(scene_file("moving-1000"), /*lockstep=*/true);
  FakeClient& c = run.join({});
  c.acks = false;
  run.ticks(3);
  ASSERT_EQ(run.feeds().unacknowledged(1), 3u);
  const std::uint64_t first = c.last_tick - 2;
  EXPECT_EQ(run.feeds().ack(1, first), server::AckResult::Accepted);
  EXPECT_EQ(run.feeds().unacknowledged(1), 2u);
  EXPECT_EQ(run.feeds().ack(1, c.last_tick), server::AckResult::Accepted);
  EXPECT_EQ(run.feeds().unacknowledged(1), 0u);
}

// Two clients whose settings differ in one field alone never share a view, and each
// stays within its own tolerances (checked on the ticks it is sent a snapshot). A
// field that ViewSettings::operator== forgot would put the second client in the
// first one's view: with a finer tolerance, it would get the first one's coarser one.
struct OneField {
  const char* name;
  void (*change)(wire::ViewSettings&);
};

class ViewSettingsField : public ::testing::TestWithParam<OneField> {};

TEST_P(ViewSettingsField, ClientsDifferingInItAloneNeverShareAView) {
  const wire::ViewSettings first;
  wire::ViewSettings second;
  GetParam().change(second);
  EXPECT_FALSE(first == second);
  FeedRun run(scene_file("moving-1000"));
  run.join(first);
  run.join(second);
  for (int i = 0; i < 90; ++i) {
    run.tick();
    ASSERT_FALSE(::testing::Test::HasFatalFailure());
    EXPECT_EQ(run.feeds().view_members(1), 1u) << "tick " << run.frame().tick;
    EXPECT_EQ(run.feeds().view_members(2), 1u) << "tick " << run.frame().tick;
    for (server::FeedClient id = 1; id <= 2; ++id) {
      const FakeClient& c = run.client(id);
      if (c.last_tick != run.frame().tick) continue;
      const auto [position, velocity] = run.worst_error(c);
      ASSERT_LE(position, c.settings.position_tolerance) << "client " << id;
      ASSERT_LE(velocity, c.settings.velocity_tolerance) << "client " << id;
    }
  }
  EXPECT_EQ(run.feeds().view_count(), 2u);
}

INSTANTIATE_TEST_SUITE_P(
    Feeds, ViewSettingsField,
    ::testing::Values(
        OneField{"encoding",
                 [](wire::ViewSettings& s) { s.encoding = physics::wire::ENCODING_EXACT; }},
        OneField{"position_precision", [](wire::ViewSettings& s) { s.quantum.position = 0.0005; }},
        OneField{"velocity_precision", [](wire::ViewSettings& s) { s.quantum.velocity = 0.0005; }},
        OneField{"position_tolerance", [](wire::ViewSettings& s) { s.position_tolerance = 0.001; }},
        OneField{"velocity_tolerance", [](wire::ViewSettings& s) { s.velocity_tolerance = 0.01; }},
        OneField{"snapshot_interval", [](wire::ViewSettings& s) { s.snapshot_interval = 2; }},
        OneField{"window", [](wire::ViewSettings& s) { s.window = 6; }},
        OneField{"interest_radius",
                 [](wire::ViewSettings& s) {
                   s.interest = wire::InterestKind::Radius;
                   s.interest_radius = 1e6;
                 }},
        OneField{"interest_rect",
                 [](wire::ViewSettings& s) {
                   s.interest = wire::InterestKind::Rect;
                   s.interest_rect.set_min_x(-1e6);
                   s.interest_rect.set_min_y(-1e6);
                   s.interest_rect.set_max_x(1e6);
                   s.interest_rect.set_max_y(1e6);
                 }},
        OneField{"byte_budget", [](wire::ViewSettings& s) { s.byte_budget = 1u << 20; }},
        OneField{"state_hash", [](wire::ViewSettings& s) { s.state_hash = true; }},
        OneField{"view_hash_interval", [](wire::ViewSettings& s) { s.view_hash_interval = 1; }}),
    [](const ::testing::TestParamInfo<OneField>& field) { return std::string(field.param.name); });

}  // namespace
}  // namespace server_test
