// Kinematic bodies reach every client, in every encoding (docs/PROTOCOL.md 5): the
// full encoding lists them each tick, the exact encoding holds them bit for bit, the
// predicted encoding glides them and sends them again only when their path changes,
// the view hash covers them, and the input relay carries what the rules do to them.
// Socket-free, on scenes/rules-room.textproto, whose lift and pusher move by their
// velocity (0.5 and 1 m/s along x).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <memory>
#include <optional>

#include "feed_run.h"
#include "relay/follow_relay.h"
#include "server/game_rules.h"
#include "server/relay_log.h"

namespace server_test {
namespace {

constexpr double kLiftSpeed = 0.5;  // m/s along x, the scene's

wire::ViewSettings view_of(physics::wire::Encoding encoding) {
  wire::ViewSettings s;
  s.encoding = encoding;
  return s;
}

std::uint64_t body_named(const server::Simulation& sim, const char* name) {
  const std::optional<phys::BodyId> id = sim.world().find_body(name);
  EXPECT_TRUE(id.has_value()) << name;
  return id ? id->packed() : 0;
}

phys::BodyState world_body(const server::Simulation& sim, std::uint64_t id) {
  const std::optional<phys::BodyState> body = sim.world().body(phys::BodyId::from_packed(id));
  EXPECT_TRUE(body.has_value()) << id;
  return body.value_or(phys::BodyState{});
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// The rules turn the lift around at tick 40 and put it elsewhere at tick 80.
class LiftRules : public server::GameRules {
 public:
  void after_step(server::GameWorld& w) override {
    const std::optional<phys::BodyId> lift = w.find_body("lift");
    if (!lift) return;
    if (w.tick() == kTurn) {
      EXPECT_TRUE(w.set_velocity(*lift, {-0.5, 0.25}));
    }
    if (w.tick() == kMove) {
      EXPECT_TRUE(w.set_position(*lift, {3.0, 6.0}));
    }
  }
  static constexpr std::uint64_t kTurn = 40;
  static constexpr std::uint64_t kMove = 80;
};

TEST(KinematicViews, TheFullEncodingCarriesTheLiftAtItsVelocityEveryTick) {
  FeedRun run(scene_file("rules-room"));
  FakeClient& full = run.spectate(view_of(physics::wire::ENCODING_FULL));
  full.keep_log = true;
  const std::uint64_t lift = body_named(run.sim(), "lift");
  const std::uint64_t pusher = body_named(run.sim(), "pusher");
  const double dt = 1.0 / run.sim().tick_rate();
  std::optional<double> last_x;
  for (int i = 0; i < 120; ++i) {
    run.tick();
    ASSERT_FALSE(full.log.empty());
    const physics::wire::Snapshot& snapshot = full.log.back();
    ASSERT_EQ(snapshot.tick(), run.frame().tick);
    const physics::wire::BodyState* sent = nullptr;
    bool pusher_sent = false;
    for (const physics::wire::BodyState& b : snapshot.bodies()) {
      if (b.body_id() == lift) sent = &b;
      if (b.body_id() == pusher) pusher_sent = true;
    }
    ASSERT_NE(sent, nullptr) << "tick " << snapshot.tick();
    EXPECT_TRUE(pusher_sent) << "tick " << snapshot.tick();
    const phys::BodyState truth = world_body(run.sim(), lift);
    ASSERT_TRUE(same_bits(sent->x(), truth.position.x)) << "tick " << snapshot.tick();
    ASSERT_TRUE(same_bits(sent->y(), truth.position.y));
    EXPECT_EQ(sent->vx(), kLiftSpeed);
    EXPECT_EQ(sent->vy(), 0.0);
    if (last_x) {
      ASSERT_NEAR(sent->x() - *last_x, kLiftSpeed * dt, 1e-12) << snapshot.tick();
    }
    last_x = sent->x();
  }
  EXPECT_NEAR(*last_x - (-2.0), kLiftSpeed * 120 * dt, 1e-9);
}

TEST(KinematicViews, TheExactEncodingHoldsTheLiftBitForBitThroughTheRulesChanges) {
  FeedRun run(scene_file("rules-room"), false, 60, std::make_shared<LiftRules>());
  FakeClient& exact = run.spectate(view_of(physics::wire::ENCODING_EXACT));
  const std::uint64_t lift = body_named(run.sim(), "lift");
  for (int i = 0; i < 120; ++i) {
    run.tick();
    ASSERT_TRUE(run.holds_mirror(exact)) << "tick " << run.frame().tick;
    wire::Reconstruction now = exact.held;
    now.advance_to(run.frame().tick, run.predictor());
    const wire::PredictedBody* held = now.find(lift);
    ASSERT_NE(held, nullptr) << "tick " << run.frame().tick;
    const phys::BodyState truth = world_body(run.sim(), lift);
    ASSERT_TRUE(same_bits(held->x, truth.position.x)) << "tick " << run.frame().tick;
    ASSERT_TRUE(same_bits(held->y, truth.position.y)) << "tick " << run.frame().tick;
    ASSERT_TRUE(same_bits(held->vx, truth.velocity.x)) << "tick " << run.frame().tick;
    ASSERT_TRUE(same_bits(held->vy, truth.velocity.y)) << "tick " << run.frame().tick;
  }
  // The rules' changes happened: the lift is where they put it, going their way.
  const phys::BodyState lift_now = world_body(run.sim(), lift);
  EXPECT_EQ(lift_now.velocity.x, -0.5);
  EXPECT_GT(lift_now.position.y, 6.0);
}

TEST(KinematicViews, ThePredictedEncodingGlidesTheLiftAndSendsItOncePerPath) {
  FeedRun run(scene_file("rules-room"), false, 60, std::make_shared<LiftRules>());
  FakeClient& predicted = run.spectate(view_of(physics::wire::ENCODING_PREDICTED));
  const std::uint64_t lift = body_named(run.sim(), "lift");
  const std::uint64_t pusher = body_named(run.sim(), "pusher");
  for (int i = 0; i < 120; ++i) {
    run.tick();
    ASSERT_TRUE(run.holds_mirror(predicted)) << "tick " << run.frame().tick;
    wire::Reconstruction now = predicted.held;
    now.advance_to(run.frame().tick, run.predictor());
    const wire::PredictedBody* held = now.find(lift);
    ASSERT_NE(held, nullptr);
    EXPECT_EQ(held->mode, wire::PredictorMode::Glide) << "tick " << run.frame().tick;
    EXPECT_EQ(now.find(pusher)->mode, wire::PredictorMode::Glide);
    const phys::BodyState truth = world_body(run.sim(), lift);
    ASSERT_LE(std::fabs(held->x - truth.position.x), predicted.settings.position_tolerance);
    ASSERT_LE(std::fabs(held->y - truth.position.y), predicted.settings.position_tolerance);
    ASSERT_LE(std::fabs(held->vx - truth.velocity.x), predicted.settings.velocity_tolerance);
    ASSERT_LE(std::fabs(held->vy - truth.velocity.y), predicted.settings.velocity_tolerance);
    // A path that holds costs nothing after its first record: one record for the
    // first path, one when the rules turn the lift, one when they move it.
    const std::uint64_t paths = 1 + (run.frame().tick >= LiftRules::kTurn ? 1 : 0) +
                                (run.frame().tick >= LiftRules::kMove ? 1 : 0);
    ASSERT_EQ(predicted.records_of[lift], paths) << "tick " << run.frame().tick;
  }
  // The pusher's path never changed (it pushes the crate; nothing pushes it).
  EXPECT_EQ(predicted.records_of[pusher], 1u);
}

TEST(KinematicViews, TheViewHashCoversTheLift) {
  FeedRun run(scene_file("rules-room"));
  FakeClient& predicted = run.spectate(view_of(physics::wire::ENCODING_PREDICTED));
  const std::uint64_t lift = body_named(run.sim(), "lift");
  run.ticks(60);
  const server::View* view = run.feeds().view_of(predicted.id);
  ASSERT_NE(view, nullptr);
  wire::Reconstruction right = predicted.held;
  right.advance_to(view->mirror().tick(), run.predictor());
  ASSERT_EQ(right.hash(), view->mirror().hash());
  const wire::PredictedBody* held = right.find(lift);
  ASSERT_NE(held, nullptr);

  // The lift a millimetre off (an exact record at the same tick keeps its mode).
  wire::Reconstruction off = right;
  physics::wire::Snapshot nudge;
  nudge.set_tick(right.tick());
  physics::wire::ExactBodies& record = *nudge.mutable_exact();
  record.add_id_gaps(lift);
  record.add_x(held->x + 0.001);
  record.add_y(held->y);
  record.add_vx(held->vx);
  record.add_vy(held->vy);
  ASSERT_EQ(off.apply(nudge, run.predictor(), predicted.settings.quantum), "");
  EXPECT_NE(off.hash(), view->mirror().hash());

  // The lift not held at all, as a client that drops kinematic bodies would.
  wire::Reconstruction without = right;
  physics::wire::Snapshot forget;
  forget.set_tick(right.tick());
  forget.add_left_gaps(lift);
  ASSERT_EQ(without.apply(forget, run.predictor(), predicted.settings.quantum), "");
  ASSERT_EQ(without.find(lift), nullptr);
  EXPECT_NE(without.hash(), view->mirror().hash());
}

// A world without kinematic bodies reads the same bodies as before they were sent:
// the dynamic ones, so its snapshots are what they were.
TEST(KinematicViews, AWorldWithoutKinematicBodiesSendsItsDynamicBodiesOnly) {
  FeedRun run(scene_file("moving-1000"));
  run.tick();
  EXPECT_EQ(run.frame().bodies.size(), run.sim().world().dynamic_body_count());
  for (const server::TruthBody& t : run.frame().bodies) EXPECT_FALSE(t.kinematic);
}

// The input relay's client runs the world: the lift the rules turn and move is where
// the server's is, bit for bit, at every tick (RelaySet carries the rules' changes).
TEST(KinematicViews, TheRelayCarriesWhatTheRulesDoToTheLift) {
  server::Simulation sim(scene_file("rules-room"), {}, std::make_shared<LiftRules>());
  server::RelayLog log;
  sim.relay_to(&log);
  std::optional<phys::World> follower = phys::World::from_bytes(sim.world().to_bytes());
  ASSERT_TRUE(follower.has_value());
  const phys::BodyId lift = *sim.world().find_body("lift");
  std::uint64_t sent = sim.current_tick();
  const std::uint64_t first_change = log.next_change();
  int sets = 0;
  for (int i = 0; i < 120; ++i) {
    sim.step_tick();
    physics::wire::Snapshot snapshot;
    log.append(sent, sim.current_tick(), first_change, 1, server::RelayLog::Audience::Followers,
               snapshot);
    sent = sim.current_tick();
    for (const physics::wire::RelayTick& tick : snapshot.relay()) {
      for (const physics::wire::RelayChange& change : tick.after_step()) {
        if (change.has_set() && change.set().body_id() == lift.packed()) ++sets;
      }
      const relay::FollowResult result = relay::follow(*follower, tick, sim.dt());
      ASSERT_EQ(result.problem, relay::FollowProblem::None) << result.detail;
    }
    const phys::BodyState theirs = *follower->body(lift);
    const phys::BodyState ours = *sim.world().body(lift);
    ASSERT_TRUE(same_bits(theirs.position.x, ours.position.x)) << "tick " << sim.current_tick();
    ASSERT_TRUE(same_bits(theirs.position.y, ours.position.y)) << "tick " << sim.current_tick();
    ASSERT_TRUE(same_bits(theirs.velocity.x, ours.velocity.x)) << "tick " << sim.current_tick();
    ASSERT_TRUE(same_bits(theirs.velocity.y, ours.velocity.y)) << "tick " << sim.current_tick();
    ASSERT_EQ(follower->state_hash(), sim.world().state_hash()) << "tick " << sim.current_tick();
  }
  EXPECT_EQ(sets, 2);  // the turn and the move
}

}  // namespace
}  // namespace server_test
