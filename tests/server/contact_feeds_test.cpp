// Contact events through the snapshot feeds: each subscriber gets the events it
// asked for, exactly as the world produced them and in order, a client that did not
// subscribe gets none, and events wait for the next snapshot sent (when none is due,
// or the window is full), bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "feed_run.h"
#include "server/simulation.h"
#include "snapshot_feeds.h"
#include "test_scene.h"
#include "truth_frame.h"

namespace server_test {
namespace {

using server::ContactFilter;
using server::FeedClient;

// The server's tick loop, reduced to what contact events go through: the world's
// events switched on while someone subscribes, every snapshot parsed as the client
// reads it (the view's bytes, then the client's own).
class EventRun {
 public:
  explicit EventRun(scene::SceneDef scene)
      : sim_(std::move(scene)),
        feeds_(wire::Predictor(sim_.tick_rate(), sim_.world().settings().gravity.x,
                               sim_.world().settings().gravity.y),
               60, false) {}

  FeedClient join_player(const wire::ViewSettings& settings = {}) {
    const FeedClient id = next_id_++;
    const auto body = sim_.join(id);
    EXPECT_TRUE(body.has_value());
    own_[id] = body->packed();
    feeds_.join(id, settings, body->packed());
    return id;
  }
  FeedClient join_spectator(const wire::ViewSettings& settings = {}) {
    const FeedClient id = next_id_++;
    feeds_.join(id, settings, std::nullopt);
    return id;
  }

  void tick() {
    sim_.set_contact_events(feeds_.any_contact_subscriber());
    const server::TickResult result = sim_.step_tick();
    const server::TruthFrame frame = server::read_truth(sim_.world(), result.tick, nullptr);
    produced_.insert(produced_.end(), frame.contact_events.begin(), frame.contact_events.end());
    const auto outputs =
        feeds_.after_tick(frame, sim_.world(), [](FeedClient) { return server::ClientFields{}; });
    for (const server::FeedOutput& out : outputs) {
      physics::wire::Snapshot snapshot;
      ASSERT_TRUE(snapshot.ParseFromString(*out.shared + out.tail));
      ASSERT_LE(snapshot.contact_events_size(),
                static_cast<int>(server::kMaxContactEventsPerSnapshot));
      auto& got = received_[out.client];
      for (const auto& e : snapshot.contact_events()) {
        ASSERT_LE(e.tick(), snapshot.tick());
        got.push_back(e);
      }
      dropped_[out.client] += snapshot.contact_events_dropped();
      ++snapshots_[out.client];
      if (!no_acks_.count(out.client)) {
        ASSERT_EQ(feeds_.ack(out.client, out.tick), server::AckResult::Accepted);
      }
    }
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }

  // What a subscriber with `filter` should have been sent: the world's events of
  // every tick so far that match, in order.
  std::vector<phys::ContactEvent> expected(const ContactFilter& filter,
                                           std::optional<std::uint64_t> own) const {
    std::vector<phys::ContactEvent> out;
    for (const auto& e : produced_) {
      if (filter.matches(e, own)) out.push_back(e);
    }
    return out;
  }
  static bool same(const std::vector<phys::ContactEvent>& want,
                   const std::vector<physics::wire::ContactEvent>& got) {
    if (want.size() != got.size()) return false;
    for (std::size_t i = 0; i < want.size(); ++i) {
      const auto& w = want[i];
      const auto& g = got[i];
      if (g.end() != (w.kind == phys::ContactEventKind::End) || g.tick() != w.step ||
          g.body_a() != w.a.packed() || g.body_b() != w.b.packed() || g.point().x() != w.point.x ||
          g.point().y() != w.point.y || g.normal().x() != w.normal.x ||
          g.normal().y() != w.normal.y || g.closing_speed() != w.closing_speed) {
        return false;
      }
    }
    return true;
  }

  server::Simulation& sim() { return sim_; }
  server::SnapshotFeeds& feeds() { return feeds_; }
  const std::vector<phys::ContactEvent>& produced() const { return produced_; }
  std::vector<physics::wire::ContactEvent>& received(FeedClient c) { return received_[c]; }
  std::uint64_t dropped(FeedClient c) { return dropped_[c]; }
  std::uint64_t snapshots(FeedClient c) { return snapshots_[c]; }
  std::uint64_t own(FeedClient c) { return own_.at(c); }
  void stop_acking(FeedClient c) { no_acks_.insert(c); }
  void resume_acking(FeedClient c) { no_acks_.erase(c); }

 private:
  server::Simulation sim_;
  server::SnapshotFeeds feeds_;
  FeedClient next_id_ = 1;
  std::map<FeedClient, std::uint64_t> own_;
  std::vector<phys::ContactEvent> produced_;
  std::map<FeedClient, std::vector<physics::wire::ContactEvent>> received_;
  std::map<FeedClient, std::uint64_t> dropped_;
  std::map<FeedClient, std::uint64_t> snapshots_;
  std::set<FeedClient> no_acks_;
};

ContactFilter all() { return {ContactFilter::Kind::All, {}}; }

TEST(ContactFeeds, EachSubscriberGetsItsEventsAndANonSubscriberNone) {
  EventRun run(scene::default_scene());
  const FeedClient player = run.join_player();
  const FeedClient quiet = run.join_player();
  const FeedClient watcher = run.join_spectator();
  const FeedClient listing = run.join_spectator();
  run.feeds().subscribe_contacts(player, {});
  run.feeds().subscribe_contacts(watcher, all());
  const ContactFilter listed{ContactFilter::Kind::Bodies, {run.own(quiet)}};
  run.feeds().subscribe_contacts(listing, listed);
  run.ticks(180);
  // The players' balls land on the floor, the scene's bodies fall and bounce.
  ASSERT_GT(run.produced().size(), 5u);
  EXPECT_TRUE(run.same(run.expected(all(), std::nullopt), run.received(watcher)));
  const auto own = run.expected({}, run.own(player));
  ASSERT_FALSE(own.empty()) << "the player's ball lands";
  EXPECT_TRUE(run.same(own, run.received(player)));
  const auto quiets = run.expected(listed, std::nullopt);
  ASSERT_FALSE(quiets.empty());
  EXPECT_TRUE(run.same(quiets, run.received(listing)));
  EXPECT_TRUE(run.received(quiet).empty());
  EXPECT_GT(run.snapshots(quiet), 0u);
}

TEST(ContactFeeds, NobodySubscribedMeansTheWorldMakesNoEvents) {
  EventRun run(scene::default_scene());
  const FeedClient player = run.join_player();
  const FeedClient watcher = run.join_spectator();
  run.ticks(60);
  EXPECT_FALSE(run.sim().world().contact_events_on());
  EXPECT_EQ(run.sim().world().counters().contact_pair_tests, 0u);
  run.feeds().subscribe_contacts(watcher, all());
  run.tick();
  EXPECT_TRUE(run.sim().world().contact_events_on());
  run.feeds().leave(watcher);
  run.tick();
  EXPECT_FALSE(run.sim().world().contact_events_on());
  const std::uint64_t tests = run.sim().world().counters().contact_pair_tests;
  run.ticks(10);
  EXPECT_EQ(run.sim().world().counters().contact_pair_tests, tests);
  EXPECT_TRUE(run.received(player).empty());
}

TEST(ContactFeeds, EventsOfTicksWithoutASnapshotComeWithTheNextOne) {
  EventRun run(scene::default_scene());
  wire::ViewSettings every_fifth;
  every_fifth.snapshot_interval = 5;
  const FeedClient sparse = run.join_spectator(every_fifth);
  wire::ViewSettings narrow;
  narrow.window = 2;
  const FeedClient stalled = run.join_spectator(narrow);
  run.feeds().subscribe_contacts(sparse, all());
  run.feeds().subscribe_contacts(stalled, all());
  run.stop_acking(stalled);
  run.ticks(120);
  EXPECT_EQ(run.snapshots(stalled), 2u);  // its window is full: the rest are skipped
  EXPECT_EQ(run.snapshots(sparse), 24u);
  EXPECT_TRUE(run.same(run.expected(all(), std::nullopt), run.received(sparse)));
  ASSERT_LT(run.received(stalled).size(), run.expected(all(), std::nullopt).size());
  // It reads again: the next snapshot brings every event it missed.
  ASSERT_EQ(run.feeds().ack(stalled, 2), server::AckResult::Accepted);
  run.resume_acking(stalled);
  run.tick();
  EXPECT_TRUE(run.same(run.expected(all(), std::nullopt), run.received(stalled)));
  EXPECT_EQ(run.dropped(stalled), 0u);
}

TEST(ContactFeeds, BeyondThePendingLimitEventsAreDroppedAndCounted) {
  EventRun run(scene_file("circle-pile"));
  wire::ViewSettings narrow;
  narrow.window = 1;
  const FeedClient stalled = run.join_spectator(narrow);
  run.feeds().subscribe_contacts(stalled, all());
  run.stop_acking(stalled);
  run.tick();
  const std::size_t first = run.received(stalled).size();  // in its one snapshot
  int ticks = 0;
  while (run.produced().size() - first < server::kMaxPendingContactEvents + 100 && ticks < 3000) {
    run.tick();
    ++ticks;
  }
  ASSERT_GE(run.produced().size() - first, server::kMaxPendingContactEvents + 100)
      << "the pile makes enough events";
  EXPECT_EQ(run.snapshots(stalled), 1u);
  ASSERT_EQ(run.feeds().ack(stalled, 1), server::AckResult::Accepted);
  run.resume_acking(stalled);
  // The 1024 held go out 256 a snapshot, the count of the lost with the first. The
  // events of this tick found the list full too.
  run.tick();
  EXPECT_EQ(run.received(stalled).size(), first + server::kMaxContactEventsPerSnapshot);
  EXPECT_EQ(run.dropped(stalled), run.produced().size() - first - server::kMaxPendingContactEvents);
  run.ticks(10);
  EXPECT_GE(run.received(stalled).size(), first + server::kMaxPendingContactEvents);
}

}  // namespace
}  // namespace server_test
