// What a rollback must and must not do, each checked by its outcome within a
// bounded number of ticks: another player's changed input is never taken for a
// match; a rollback moves no body on screen, and its correction then glides the
// shown position onto the new prediction.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "client/prediction_core.h"
#include "prediction_loop.h"

namespace predicting_test {
namespace {

double distance(client::Vec2 a, client::Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

std::map<std::uint64_t, client::RenderBody> shown_bodies(const client::PredictionCore& core) {
  std::map<std::uint64_t, client::RenderBody> bodies;
  for (const client::RenderBody& body : core.render().bodies) bodies[body.body_id] = body;
  return bodies;
}

// The relayed ticks of a loop whose deliveries are held back, one at a time, until
// the one that rolls back (at most `limit`). False if none did.
bool deliver_until_rollback(PredictionLoop& loop, int limit) {
  for (int i = 0; i < limit && !loop.in_flight.empty(); ++i) {
    const std::uint64_t before = loop.core.stats().rollbacks;
    loop.deliver_one();
    if (loop.core.stats().rollbacks > before) return true;
  }
  return false;
}

TEST(RollbackChecks, AnotherPlayersChangedInputIsNeverTakenForAMatch) {
  PredictionLoop loop;
  for (int i = 0; i < 30; ++i) loop.round(circling);
  ASSERT_EQ(loop.core.stats().rollbacks, 0u);
  const std::uint64_t changed = loop.server.tick() + 1;
  loop.server.input(loop.other(), changed, {0.0, 25.0});
  loop.latency = 1000;  // held back: delivered one by one below
  for (int i = 0; i < 8; ++i) loop.round(circling);
  ASSERT_TRUE(deliver_until_rollback(loop, 20));
  EXPECT_EQ(loop.core.confirmed_tick(), changed);
  EXPECT_EQ(loop.core.stats().rollbacks, 1u);
  EXPECT_EQ(loop.core.stats().desyncs, 0u);
  EXPECT_FALSE(loop.core.awaiting_full_state());
  EXPECT_EQ(loop.core.confirmed_hash(), loop.server.hashes().at(changed));
}

TEST(RollbackChecks, ARollbackMovesNoBodyOnScreenAndItsCorrectionGlides) {
  PredictionLoop loop;
  for (int i = 0; i < 30; ++i) loop.round(circling);
  loop.server.input(loop.other(), loop.server.tick() + 1, {-45.0, 0.0});
  loop.latency = 1000;
  for (int i = 0; i < 8; ++i) loop.round(circling);
  // Delivered one by one; the screen just before the delivery that rolls back.
  std::map<std::uint64_t, client::RenderBody> before;
  bool rolled_back = false;
  for (int i = 0; i < 20 && !rolled_back && !loop.in_flight.empty(); ++i) {
    before = shown_bodies(loop.core);
    const std::uint64_t rollbacks = loop.core.stats().rollbacks;
    loop.deliver_one();
    rolled_back = loop.core.stats().rollbacks > rollbacks;
  }
  ASSERT_TRUE(rolled_back);
  const std::map<std::uint64_t, client::RenderBody> after = shown_bodies(loop.core);
  const client::RenderBody& moved = after.at(loop.other());
  const client::Vec2 old_prediction = before.at(loop.other()).predicted_position;
  // The prediction did change, by more than a rounding error...
  ASSERT_GT(distance(moved.predicted_position, old_prediction), 1e-3);
  // ...yet every body is shown where it was.
  for (const auto& [id, body] : after) {
    EXPECT_LT(distance(body.position, before.at(id).position), 1e-9) << "body " << id;
  }
  // Each tick from then on, the shown position gets closer to the new prediction,
  // and never moves away from it.
  double gap = distance(moved.position, moved.predicted_position);
  for (int i = 0; i < 12; ++i) {
    loop.round(circling);
    const client::RenderBody now = shown_bodies(loop.core).at(loop.other());
    const double next = distance(now.position, now.predicted_position);
    EXPECT_LT(next, gap) << "tick " << i;
    gap = next;
  }
  EXPECT_LT(gap, 0.2 * distance(moved.predicted_position, old_prediction));
}

}  // namespace
}  // namespace predicting_test
