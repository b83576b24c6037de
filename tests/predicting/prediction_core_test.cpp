// The rollback loop against an in-process relay: what it rolls back, when, and that
// its confirmed state is the server's.
#include "client/prediction_core.h"

#include <gtest/gtest.h>

#include "prediction_loop.h"

namespace predicting_test {
namespace {

TEST(Rollback, NeverWhenEveryInputIsPredictedRight) {
  PredictionLoop loop;
  // The other player pushes constantly from before the client joined: held.
  loop.server.input(loop.other(), 0, {3.0, 0.0});
  loop.server.step();
  loop.core.start(loop.server.copy(), loop.server.tick(), loop.own(), loop.server.tick_rate());
  for (int i = 0; i < 300; ++i) loop.round(circling);
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_EQ(stats.rollbacks, 0u);
  EXPECT_EQ(stats.resimulated_ticks, 0u);
  EXPECT_GT(stats.confirmed_ticks, 250u);
  EXPECT_EQ(stats.matched_ticks, stats.confirmed_ticks);
  EXPECT_EQ(stats.hashes_checked, stats.confirmed_ticks);
  EXPECT_EQ(stats.desyncs, 0u);
  EXPECT_EQ(loop.core.predicted_tick(), loop.server.tick() - 1 + loop.lead);
}

TEST(Rollback, AnotherPlayersNewInputRollsBackTheTicksInFlight) {
  PredictionLoop loop;
  for (int i = 0; i < 60; ++i) loop.round(circling);
  ASSERT_EQ(loop.core.stats().rollbacks, 0u);
  // The other player changes its input at the next server tick.
  loop.server.input(loop.other(), loop.server.tick() + 1, {0.0, 20.0});
  const std::uint64_t changed = loop.server.tick() + 1;
  while (loop.core.confirmed_tick() + 1 < changed || loop.core.stats().rollbacks == 0) {
    loop.round(circling);
  }
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_EQ(stats.rollbacks, 1u);
  EXPECT_EQ(loop.core.confirmed_tick(), changed);
  // Every predicted tick after the confirmed one was stepped again, and no other.
  EXPECT_EQ(loop.before_delivery, loop.lead + loop.latency);
  EXPECT_EQ(stats.resimulated_ticks, loop.before_delivery);
  // From then on the new input is held: predicted right again.
  for (int i = 0; i < 60; ++i) loop.round(circling);
  EXPECT_EQ(loop.core.stats().rollbacks, 1u);
  EXPECT_EQ(loop.core.stats().desyncs, 0u);
}

TEST(Rollback, ConfirmedStateIsTheServersAtEveryHashTick) {
  PredictionLoop loop(8, 5, 3);
  std::uint64_t compared = 0;
  std::uint64_t seen = loop.core.confirmed_tick();
  std::uint64_t joined = 0;
  for (int i = 0; i < 400; ++i) {
    // The other player changes its input every 17 ticks; a body joins and one leaves.
    if (i % 17 == 5) {
      loop.server.input(loop.other(), loop.server.tick() + 1,
                        {static_cast<double>(i % 7) - 3.0, static_cast<double>(i % 5)});
    }
    if (i == 100) joined = loop.server.join_next_tick(loop.server.player_def(-5.0));
    if (i == 200) loop.server.leave_next_tick(joined);
    loop.round(circling);
    if (loop.core.confirmed_tick() != seen) {
      seen = loop.core.confirmed_tick();
      if (seen % 3 == 0) {
        EXPECT_EQ(loop.core.confirmed_hash(), loop.server.hashes().at(seen)) << "tick " << seen;
        ++compared;
      }
    }
  }
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_GT(compared, 100u);
  EXPECT_EQ(stats.desyncs, 0u);
  EXPECT_EQ(stats.bad_changes, 0u);
  EXPECT_GT(stats.hashes_checked, 100u);
  EXPECT_GE(stats.rollbacks, 20u);  // 24 input changes, a join, a leave
  EXPECT_FALSE(loop.core.awaiting_full_state());
}

TEST(Rollback, OwnInputShowsInTheVeryNextPredictedTick) {
  PredictionLoop loop;
  for (int i = 0; i < 30; ++i) loop.round([](std::uint64_t) { return client::Vec2{}; });
  const std::uint64_t before = loop.core.predicted_tick();
  const phys::BodyId own = phys::BodyId::from_packed(loop.own());
  // What the next tick would be without the new input.
  phys::World without(loop.core.predicted_world().save());
  without.step(loop.core.dt());
  loop.core.set_input(before + 1, {0.0, 40.0});
  loop.core.advance_to(before + 1);
  ASSERT_EQ(loop.core.predicted_tick(), before + 1);
  const auto shown = loop.core.predicted_world().body(own);
  ASSERT_TRUE(shown);
  EXPECT_EQ(shown->acceleration, (phys::Vec2{0.0, 40.0}));
  EXPECT_GT(shown->velocity.y, without.body(own)->velocity.y);
  // And render() shows it as well.
  const client::RenderState render = loop.core.render();
  EXPECT_EQ(render.tick, before + 1);
}

TEST(Rollback, OwnInputAppliedLaterThanPredictedRollsBack) {
  PredictionLoop loop;
  loop.own_late_by = 1;  // the server applies each own input a tick after its own tick
  for (int i = 0; i < 100; ++i) loop.round(circling);
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_GT(stats.rollbacks, 80u);  // every own input differs by a tick
  EXPECT_EQ(stats.desyncs, 0u);
  EXPECT_EQ(loop.core.confirmed_hash(), loop.server.hashes().at(loop.core.confirmed_tick()));
}

TEST(Rollback, OwnInputOverTheLimitIsPredictedAsTheServerClampsIt) {
  PredictionLoop loop;
  const double limit = loop.server.max_acceleration();
  ASSERT_GT(limit, 0.0);
  // Over the scene's limit, off the axes (where clamping rounds), changed every 20
  // ticks: the server applies and relays each clamped; the prediction must too.
  const auto over = [&](std::uint64_t tick) {
    const double k = static_cast<double>(tick / 20 % 3 + 2);
    return client::Vec2{k * limit, -0.7 * k * limit};
  };
  for (int i = 0; i < 120; ++i) loop.round(over);
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_GT(stats.confirmed_ticks, 100u);
  EXPECT_EQ(stats.rollbacks, 0u);
  EXPECT_EQ(stats.matched_ticks, stats.confirmed_ticks);
  EXPECT_EQ(stats.desyncs, 0u);
  const auto own = loop.core.predicted_world().body(phys::BodyId::from_packed(loop.own()));
  ASSERT_TRUE(own);
  EXPECT_LE(phys::length(own->acceleration), limit);
  EXPECT_GT(phys::length(own->acceleration), 0.99 * limit);
}

TEST(Rollback, TheBarrierStopsThePredictionAtMaxRollbackTicksPastTheConfirmed) {
  client::PredictionConfig config;
  config.max_rollback = 10;
  PredictionLoop loop(6, 4, 1, config);
  // Nothing is delivered for 40 rounds: the prediction runs 10 ticks ahead, no further.
  loop.latency = 40;
  for (int i = 0; i < 40; ++i) loop.round(circling);
  EXPECT_EQ(loop.core.predicted_tick(), loop.core.confirmed_tick() + 10);
  EXPECT_GT(loop.core.stats().barrier_waits, 0u);
  // The other player's change arrives: the rollback is at most 10 ticks deep.
  loop.server.input(loop.other(), loop.server.tick() + 1, {0.0, 20.0});
  loop.latency = 0;
  for (int i = 0; i < 5; ++i) loop.round(circling);
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_GE(stats.rollbacks, 1u);
  EXPECT_LE(stats.resimulated_ticks, 10u * stats.rollbacks);
  EXPECT_EQ(stats.deep_rollbacks, 0u);
  EXPECT_EQ(stats.desyncs, 0u);
  EXPECT_EQ(loop.core.confirmed_hash(), loop.server.hashes().at(loop.core.confirmed_tick()));
}

TEST(Rollback, TicksPastThePredictionInOneSnapshotAreTakenWithoutARollback) {
  client::PredictionConfig config;
  config.max_rollback = 5;
  PredictionLoop loop(6, 30, 1, config);
  for (int i = 0; i < 40; ++i) loop.round(circling);
  ASSERT_EQ(loop.core.predicted_tick(), loop.core.confirmed_tick() + 5);
  // 30 ticks in one snapshot: 5 were predicted right, 25 never predicted.
  const std::vector<physics::wire::RelayTick> all(loop.in_flight.begin(), loop.in_flight.end());
  loop.in_flight.clear();
  const client::PredictionStats before = loop.core.stats();
  loop.core.on_snapshot(relay_snapshot(all));
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_EQ(stats.rollbacks, 0u);
  EXPECT_EQ(stats.matched_ticks - before.matched_ticks, 5u);
  EXPECT_EQ(stats.confirmed_ticks - before.confirmed_ticks, 30u);
  EXPECT_EQ(stats.desyncs, 0u);
  EXPECT_EQ(loop.core.confirmed_tick(), loop.server.tick());
}

TEST(Smoothing, ACorrectionDecaysExponentiallyOverTicks) {
  client::PredictionConfig config;
  config.smoothing_time_constant = 0.1;
  PredictionLoop loop(6, 4, 1, config);
  for (int i = 0; i < 30; ++i) loop.round(circling);
  // A hard change of the other player's input: its predicted position jumps.
  loop.server.input(loop.other(), loop.server.tick() + 1, {-45.0, 0.0});
  while (loop.core.stats().rollbacks == 0) loop.round(circling);
  const client::Vec2 first = loop.core.correction(loop.other());
  const double size = std::hypot(first.x, first.y);
  ASSERT_GT(size, 0.0);
  EXPECT_GT(loop.core.stats().largest_correction, 0.0);
  EXPECT_LT(loop.core.stats().largest_smoothed_correction, loop.core.stats().largest_correction);
  // The rendered position is the predicted one plus the correction.
  for (const client::RenderBody& body : loop.core.render().bodies) {
    if (body.body_id != loop.other()) continue;
    EXPECT_DOUBLE_EQ(body.position.x, body.predicted_position.x + first.x);
  }
  // Each tick shown keeps exp(-dt / 0.1) of it: after 6 ticks at 60 Hz, 1/e.
  const std::uint64_t from = loop.core.predicted_tick();
  loop.latency = 1000;  // nothing more arrives: no new correction
  for (int i = 0; i < 6; ++i) loop.round(circling);
  ASSERT_EQ(loop.core.predicted_tick(), from + 6);
  const client::Vec2 later = loop.core.correction(loop.other());
  EXPECT_NEAR(std::hypot(later.x, later.y), size * std::exp(-1.0), size * 1e-9);
}

}  // namespace
}  // namespace predicting_test
