// What the rollback loop does with a relay it cannot follow: each case counted,
// answered by a full state request or a clear error, never a crash.
#include <gtest/gtest.h>

#include "client/prediction_core.h"
#include "prediction_loop.h"

namespace predicting_test {
namespace {

// A loop that has run a while, every relayed tick delivered at once.
PredictionLoop settled() {
  PredictionLoop loop(6, 0, 1);
  for (int i = 0; i < 20; ++i) loop.round(circling);
  return loop;
}

using physics::wire::RelayTick;

RelayTick next_tick(const PredictionLoop& loop) {
  RelayTick relay;
  relay.set_tick(loop.core.confirmed_tick() + 1);
  return relay;
}

void add_body(RelayTick& relay, std::uint64_t id) {
  physics::wire::RelayBody& body = *relay.add_changes()->mutable_added();
  body.set_body_id(id);
  body.set_shape(physics::wire::SHAPE_CIRCLE);
  body.set_radius(0.5);
  body.mutable_position()->set_y(10.0);
  body.set_mass(1.0);
}

void add_input(RelayTick& relay, std::uint64_t id, double ax, double ay) {
  physics::wire::RelayInput& input = *relay.add_inputs();
  input.set_body_id(id);
  input.set_ax(ax);
  input.set_ay(ay);
}

void expect_full_state_asked(PredictionLoop& loop) {
  EXPECT_TRUE(loop.core.awaiting_full_state());
  EXPECT_TRUE(loop.core.take_full_state_request());
  EXPECT_FALSE(loop.core.take_full_state_request());  // once
  EXPECT_EQ(loop.core.stats().full_state_requests, 1u);
  EXPECT_FALSE(loop.core.failed());
  // Until the full state, relayed ticks are dropped, counted; the prediction goes on.
  const std::uint64_t confirmed = loop.core.confirmed_tick();
  loop.core.on_snapshot(relay_snapshot({next_tick(loop)}));
  EXPECT_EQ(loop.core.confirmed_tick(), confirmed);
  EXPECT_EQ(loop.core.stats().ticks_dropped, 1u);
}

TEST(RelayBadInput, AJoinForABodyAlreadyPresent) {
  PredictionLoop loop = settled();
  RelayTick relay = next_tick(loop);
  add_body(relay, loop.other());
  loop.core.on_snapshot(relay_snapshot({relay}));
  EXPECT_EQ(loop.core.stats().bad_changes, 1u);
  EXPECT_NE(loop.core.error().find("holds already"), std::string::npos) << loop.core.error();
  expect_full_state_asked(loop);
}

TEST(RelayBadInput, AJoinThatGetsAnotherIdHere) {
  PredictionLoop loop = settled();
  RelayTick relay = next_tick(loop);
  add_body(relay, phys::BodyId{900, 3}.packed());
  loop.core.on_snapshot(relay_snapshot({relay}));
  EXPECT_EQ(loop.core.stats().bad_changes, 1u);
  EXPECT_NE(loop.core.error().find("gave it"), std::string::npos) << loop.core.error();
  expect_full_state_asked(loop);
}

TEST(RelayBadInput, ALeaveOfAnUnknownBodyAndAnInputForAStaticOne) {
  PredictionLoop loop = settled();
  RelayTick relay = next_tick(loop);
  relay.add_changes()->set_removed(phys::BodyId{700, 0}.packed());
  loop.core.on_snapshot(relay_snapshot({relay}));
  EXPECT_EQ(loop.core.stats().bad_changes, 1u);
  expect_full_state_asked(loop);

  PredictionLoop other = settled();
  RelayTick input = next_tick(other);
  add_input(input, phys::BodyId{0, 0}.packed(), 1.0, 0.0);  // the floor
  other.core.on_snapshot(relay_snapshot({input}));
  EXPECT_EQ(other.core.stats().bad_changes, 1u);
  EXPECT_TRUE(other.core.awaiting_full_state());
}

TEST(RelayBadInput, TicksInThePastAreCountedAndIgnored) {
  PredictionLoop loop(6, 2, 1);
  for (int i = 0; i < 20; ++i) loop.round(circling);
  const RelayTick old = loop.in_flight.front();
  loop.deliver_one();
  const std::uint64_t confirmed = loop.core.confirmed_tick();
  const std::uint64_t hash = loop.core.confirmed_hash();
  loop.core.on_snapshot(relay_snapshot({old}));  // again
  RelayTick ancient;
  ancient.set_tick(1);
  add_input(ancient, loop.other(), 9.0, 9.0);
  loop.core.on_snapshot(relay_snapshot({ancient}));
  EXPECT_EQ(loop.core.stats().stale_ticks, 2u);
  EXPECT_EQ(loop.core.confirmed_tick(), confirmed);
  EXPECT_EQ(loop.core.confirmed_hash(), hash);
  EXPECT_FALSE(loop.core.awaiting_full_state());
  EXPECT_EQ(loop.core.stats().rollbacks, 0u);
}

TEST(RelayBadInput, AGapInTheTicksAsksForAFullState) {
  PredictionLoop loop(6, 3, 1);
  for (int i = 0; i < 20; ++i) loop.round(circling);
  loop.in_flight.pop_front();  // lost
  loop.deliver_one();
  EXPECT_EQ(loop.core.stats().gaps, 1u);
  EXPECT_NE(loop.core.error().find("missing"), std::string::npos) << loop.core.error();
  expect_full_state_asked(loop);
}

TEST(RelayBadInput, AHashThatDiffersAsksForAFullState) {
  PredictionLoop loop = settled();
  loop.server.step();  // a tick the client is not told about: its hash is not ours
  RelayTick relay = loop.server.step();
  relay.set_tick(loop.core.confirmed_tick() + 1);
  relay.clear_changes();
  relay.clear_inputs();
  loop.core.on_snapshot(relay_snapshot({relay}));
  EXPECT_EQ(loop.core.stats().desyncs, 1u);
  EXPECT_NE(loop.core.error().find("state hash"), std::string::npos) << loop.core.error();
  expect_full_state_asked(loop);
}

TEST(RelayBadInput, WorldStateBytesThatDoNotParse) {
  PredictionLoop loop = settled();
  client::Snapshot answer;
  answer.tick = loop.core.confirmed_tick() + 1;
  answer.world_state = {'n', 'o', 't', ' ', 'a', ' ', 'w', 'o', 'r', 'l', 'd'};
  loop.core.on_snapshot(answer);
  EXPECT_EQ(loop.core.stats().bad_world_states, 1u);
  EXPECT_EQ(loop.core.stats().resyncs, 0u);
  EXPECT_TRUE(loop.core.take_full_state_request());  // asked again
  EXPECT_NE(loop.core.error().find("does not parse"), std::string::npos) << loop.core.error();
  // Three in a row: the core stops, and says why.
  loop.core.on_snapshot(answer);
  loop.core.on_snapshot(answer);
  EXPECT_TRUE(loop.core.failed());
  EXPECT_EQ(loop.core.stats().bad_world_states, 3u);
  EXPECT_NE(loop.core.error().find("3 times"), std::string::npos) << loop.core.error();
  // A failed core takes nothing more, and does not crash on it.
  const std::uint64_t tick = loop.core.predicted_tick();
  loop.round(circling);
  EXPECT_EQ(loop.core.predicted_tick(), tick);
}

TEST(RelayBadInput, ARelayedTickThatDoesNotParse) {
  PredictionLoop loop = settled();
  client::Snapshot snapshot;
  snapshot.tick = loop.core.confirmed_tick() + 1;
  snapshot.relay.push_back(std::string("\xff\xff\xff", 3));
  loop.core.on_snapshot(snapshot);
  EXPECT_EQ(loop.core.stats().bad_changes, 1u);
  EXPECT_NE(loop.core.error().find("does not parse"), std::string::npos) << loop.core.error();
  expect_full_state_asked(loop);
}

TEST(RelayBadInput, AWelcomeWithoutAWorld) {
  client::PredictionCore core;
  client::Welcome welcome;
  welcome.tick_rate = 60.0;
  EXPECT_FALSE(core.start(welcome));
  EXPECT_NE(core.error().find("want_world"), std::string::npos) << core.error();
  welcome.world_state = {1, 2, 3, 4};
  EXPECT_FALSE(core.start(welcome));
  EXPECT_NE(core.error().find("does not parse"), std::string::npos) << core.error();
  EXPECT_FALSE(core.started());
}

TEST(Resync, AWelcomesWorldStartsTheCoreAtItsTick) {
  FakeServer server;
  for (int i = 0; i < 10; ++i) server.step();
  client::Welcome welcome;
  welcome.tick_rate = server.tick_rate();
  welcome.current_tick = server.tick();
  welcome.body_id = server.player(0);
  welcome.world_state = server.world().to_bytes();
  client::PredictionCore core;
  ASSERT_TRUE(core.start(welcome)) << core.error();
  EXPECT_EQ(core.confirmed_tick(), server.tick());
  EXPECT_EQ(core.confirmed_hash(), server.world().state_hash());
  EXPECT_EQ(core.own_body(), server.player(0));
}

// A full state from the server's bytes: the confirmed state is the server's again.
TEST(Resync, AFullStateRestartsTheConfirmedStateAtItsTick) {
  PredictionLoop loop = settled();
  RelayTick relay = next_tick(loop);
  relay.set_state_hash(12345);  // wrong
  loop.core.on_snapshot(relay_snapshot({relay}));
  ASSERT_TRUE(loop.core.take_full_state_request());
  client::Snapshot answer;
  answer.tick = loop.server.tick();
  answer.world_state = loop.server.world().to_bytes();
  loop.core.on_snapshot(answer);
  EXPECT_EQ(loop.core.stats().resyncs, 1u);
  EXPECT_FALSE(loop.core.awaiting_full_state());
  EXPECT_EQ(loop.core.confirmed_tick(), loop.server.tick());
  EXPECT_EQ(loop.core.confirmed_hash(), loop.server.hashes().at(loop.server.tick()));
  for (int i = 0; i < 30; ++i) loop.round(circling);
  EXPECT_EQ(loop.core.confirmed_hash(), loop.server.hashes().at(loop.core.confirmed_tick()));
  EXPECT_EQ(loop.core.stats().desyncs, 1u);
}

TEST(Resync, AHashThatNeverMatchesStopsTheCoreAfterThreeFullStates) {
  PredictionLoop loop = settled();
  for (int attempt = 0; attempt < 4 && !loop.core.failed(); ++attempt) {
    RelayTick relay = next_tick(loop);
    relay.set_state_hash(12345);  // never the world's
    loop.core.on_snapshot(relay_snapshot({relay}));
    if (loop.core.failed()) break;
    ASSERT_TRUE(loop.core.take_full_state_request());
    client::Snapshot answer;
    answer.tick = loop.server.tick();
    answer.world_state = loop.server.world().to_bytes();
    loop.core.on_snapshot(answer);
  }
  EXPECT_TRUE(loop.core.failed());
  EXPECT_EQ(loop.core.stats().resyncs, 3u);
  EXPECT_EQ(loop.core.stats().desyncs, 4u);
  EXPECT_NE(loop.core.error().find("never"), std::string::npos) << loop.core.error();
}

}  // namespace
}  // namespace predicting_test
