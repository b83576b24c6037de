// The game's rules inside the rollback (PredictionCore::set_rules), against the
// server's own Simulation running the same rules and its relay for clients that run
// them: the own message's effect in the next predicted tick, no rollback when every
// prediction is right, exactly the ticks in flight rolled back for another player's
// message, the rules' predicted messages replaced by the confirmed ones, and relays
// or worlds that cannot be the server's. No sockets, no clock.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/prediction_core.h"
#include "server/game_rules.h"
#include "server/relay_log.h"
#include "server/simulation.h"
#include "wire.pb.h"

namespace {

using server::ClientId;

constexpr ClientId kOwn = 1;
constexpr ClientId kOther = 2;

scene::SceneDef dash_scene() {
  scene::SceneDef scene;
  scene.name = "dash";
  scene.world.gravity = {0.0, -9.81};
  scene.tick_rate = 60.0;
  scene.max_acceleration = 50.0;
  scene.spawn_points = {{-4.0, 1.0}, {4.0, 1.0}};
  scene.player.shape = phys::Shape::Circle;
  scene.player.motion = phys::Motion::Dynamic;
  scene.player.radius = 0.5;
  scene.player.mass = 1.0;
  phys::BodyDef floor;
  floor.shape = phys::Shape::Box;
  floor.motion = phys::Motion::Static;
  floor.half_extents = {20.0, 0.5};
  floor.position = {0.0, -0.5};
  scene.bodies.push_back(floor);
  return scene;
}

// A small game: "dash" kicks the sender up and counts its dashes, "shoot" makes a
// shot that a timer removes, and every dash is broadcast; the last input's x of each
// player is kept as its facing. All of it in the world's game state.
class DashRules : public server::GameRules {
 public:
  void before_step(server::GameWorld& world,
                   const std::vector<server::AppliedInput>& inputs) override {
    for (const server::AppliedInput& input : inputs) {
      world.set_number("facing", input.acceleration.x >= 0.0 ? 1.0 : -1.0, input.client);
    }
    for (const server::ClientGameMessage& message : world.messages()) {
      const std::optional<phys::BodyId> body = world.body_of(message.client);
      if (!body) continue;
      if (message.payload == "dash") {
        world.apply_impulse(*body, {world.get_number("facing", message.client, 1.0) * 2.0, 6.0});
        const std::int64_t dashes = world.get_int("dashes", message.client) + 1;
        world.set_int("dashes", dashes, message.client);
        world.broadcast("dash " + std::to_string(message.client) + " " + std::to_string(dashes));
      }
      if (message.payload == "shoot") {
        phys::BodyDef shot;
        shot.shape = phys::Shape::Circle;
        shot.radius = 0.1;
        shot.mass = 0.1;
        shot.position = world.body(*body)->position + phys::Vec2{0.0, 1.0};
        shot.velocity = {5.0, 2.0};
        const phys::BodyId made = world.create(shot);
        world.start_timer("shot", 20, 0, made.packed());
      }
    }
  }
  void on_timer(server::GameWorld& world, std::string_view name, std::uint64_t index) override {
    if (name == "shot") world.destroy(phys::BodyId::from_packed(index));
  }
};

// Throws on "boom": as a rule that fails its tick.
class ThrowingRules : public DashRules {
 public:
  void after_step(server::GameWorld& world) override {
    if (world.tick() == throw_at) throw std::runtime_error("boom");
  }
  std::uint64_t throw_at = 0;
};

std::vector<client::Player> players_of(const server::Simulation& sim) {
  std::vector<client::Player> players;
  for (const auto& [client, body] : sim.room().members()) {
    client::Player& player = players.emplace_back();
    player.client_id = client;
    player.body_id = body.packed();
    if (const auto seen = sim.last_rules_input(client)) {
      player.rules_input = client::Vec2{seen->x, seen->y};
    }
  }
  return players;
}

client::Snapshot snapshot_of(const physics::wire::Snapshot& message) {
  client::Snapshot snapshot;
  snapshot.tick = message.relay_size() > 0 ? message.relay(message.relay_size() - 1).tick() : 0;
  for (const auto& tick : message.relay()) snapshot.relay.push_back(tick.SerializeAsString());
  return snapshot;
}

// The server (a Simulation with the rules and its relay) and one predicting player,
// in rounds: the player's input (and messages) for `lead` ticks ahead, the
// prediction to it, one server tick, and relayed ticks delivered `latency` rounds on.
struct RulesLoop {
  explicit RulesLoop(
      std::shared_ptr<server::GameRules> client_rules = std::make_shared<DashRules>(),
      std::uint32_t lead_ticks = 6, std::uint32_t latency_rounds = 4)
      : sim(dash_scene(), {}, std::make_shared<DashRules>()),
        lead(lead_ticks),
        latency(latency_rounds) {
    sim.relay_to(&log);
    own_body = sim.join(kOwn).value();
    other_body = sim.join(kOther).value();
    core.set_rules(std::move(client_rules));
    start_core();
  }

  void start_core() {
    core.start(phys::World::from_bytes(sim.world().to_bytes()).value(), sim.current_tick(),
               own_body.packed(), sim.tick_rate(), sim.scene().max_acceleration, players_of(sim),
               kOwn);
    sent_after = sim.current_tick();
    first_change = log.next_change();
  }

  // The own input and messages for server tick + lead, predicted at once.
  void round(phys::Vec2 own_input, const std::vector<std::string>& own_messages = {}) {
    const std::uint64_t local = sim.current_tick() + lead;
    for (const std::string& payload : own_messages) {
      core.send_message(local, payload);
      sim.submit_game_message(kOwn, local, payload);
    }
    core.set_input(local, {own_input.x, own_input.y});
    sim.submit_input(kOwn, local, own_input);
    core.advance_to(local);
    server_tick();
  }

  void server_tick() {
    sim.step_tick();
    for (server::OutgoingGameMessage& sent : sim.take_outgoing_messages()) {
      server_sent.push_back(std::move(sent));
    }
    physics::wire::Snapshot relay;
    log.append(sent_after, sim.current_tick(), first_change, 1,
               server::RelayLog::Audience::RulesRunners, relay);
    sent_after = sim.current_tick();
    in_flight.push_back(relay);
    while (in_flight.size() > latency) deliver_one();
  }

  void deliver_one() {
    before_delivery = core.predicted_tick() - core.confirmed_tick();
    core.on_snapshot(snapshot_of(in_flight.front()));
    in_flight.pop_front();
  }

  server::Simulation sim;
  server::RelayLog log;
  client::PredictionCore core;
  phys::BodyId own_body;
  phys::BodyId other_body;
  std::uint32_t lead;
  std::uint32_t latency;
  std::uint64_t sent_after = 0;
  std::uint64_t first_change = 0;
  std::deque<physics::wire::Snapshot> in_flight;
  std::vector<server::OutgoingGameMessage> server_sent;
  std::uint64_t before_delivery = 0;
};

phys::Vec2 circling(std::uint64_t tick) {
  const double angle = static_cast<double>(tick % 120) * (2.0 * 3.141592653589793 / 120.0);
  return {5.0 * std::cos(angle), 0.0};
}

TEST(RulesPrediction, NeverRollsBackWhenEveryPredictionIsRight) {
  RulesLoop loop;
  for (int i = 0; i < 300; ++i) {
    const std::uint64_t local = loop.sim.current_tick() + loop.lead;
    std::vector<std::string> messages;
    if (i % 25 == 3) messages.push_back("dash");
    if (i % 40 == 7) messages.push_back("shoot");
    loop.round(circling(local), messages);
  }
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_EQ(stats.rollbacks, 0u);
  EXPECT_EQ(stats.resimulated_ticks, 0u);
  EXPECT_GT(stats.confirmed_ticks, 280u);
  EXPECT_EQ(stats.matched_ticks, stats.confirmed_ticks);
  EXPECT_EQ(stats.hashes_checked, stats.confirmed_ticks);
  EXPECT_EQ(stats.desyncs, 0u);
  EXPECT_EQ(stats.bad_changes, 0u);
  // The game's state is in the hashes that matched: the dashes were counted alike.
  EXPECT_EQ(loop.sim.world().game_state().get_int("dashes", kOwn), 12);
  EXPECT_EQ(loop.core.confirmed_world().game_state().get_int("dashes", kOwn), 12);
}

TEST(RulesPrediction, TheOwnMessagesEffectIsInTheNextPredictedTick) {
  RulesLoop loop;
  for (int i = 0; i < 30; ++i) loop.round({1.0, 0.0});
  const std::uint64_t before = loop.core.predicted_tick();
  const double vy_before = loop.core.predicted_world().body(loop.own_body)->velocity.y;
  // The next round predicts one more tick, with the message in it.
  loop.round({1.0, 0.0}, {"dash"});
  ASSERT_EQ(loop.core.predicted_tick(), before + 1);
  // The kick (6 m/s up, less one tick of gravity) shows before the server saw it.
  EXPECT_GT(loop.core.predicted_world().body(loop.own_body)->velocity.y, vy_before + 5.0);
  EXPECT_EQ(loop.core.predicted_world().game_state().get_int("dashes", kOwn), 1);
  EXPECT_LT(loop.core.confirmed_tick(), before + 1);
  for (int i = 0; i < 20; ++i) loop.round({1.0, 0.0});
  EXPECT_EQ(loop.core.stats().rollbacks, 0u);
  EXPECT_EQ(loop.core.stats().desyncs, 0u);
}

TEST(RulesPrediction, WithoutRulesTheOwnMessageWaitsForTheServer) {
  // The bug this feature fixes: a core that does not run the rules shows the dash
  // only when the server's tick comes back, as a rollback. (A core without rules
  // needs the relay with the rules' changes: Followers.)
  server::Simulation sim(dash_scene(), {}, std::make_shared<DashRules>());
  server::RelayLog log;
  sim.relay_to(&log);
  const phys::BodyId own = sim.join(kOwn).value();
  client::PredictionCore core;
  core.start(phys::World::from_bytes(sim.world().to_bytes()).value(), sim.current_tick(),
             own.packed(), sim.tick_rate(), sim.scene().max_acceleration);
  core.send_message(sim.current_tick() + 1, "dash");
  core.set_input(sim.current_tick() + 1, {0.0, 0.0});
  core.advance_to(sim.current_tick() + 1);
  EXPECT_EQ(core.predicted_world().game_state().get_int("dashes", kOwn), std::nullopt);
  EXPECT_LT(core.predicted_world().body(own)->velocity.y, 1.0);
}

TEST(RulesPrediction, AnotherPlayersMessageRollsBackExactlyTheTicksInFlight) {
  RulesLoop loop;
  for (int i = 0; i < 40; ++i) loop.round({0.0, 0.0});
  ASSERT_EQ(loop.core.stats().rollbacks, 0u);
  const std::uint64_t at = loop.sim.current_tick() + 1;
  loop.sim.submit_game_message(kOther, at, "dash");
  while (loop.core.confirmed_tick() < at) loop.round({0.0, 0.0});
  const client::PredictionStats& stats = loop.core.stats();
  EXPECT_EQ(stats.rollbacks, 1u);
  EXPECT_EQ(loop.before_delivery, loop.lead + loop.latency);
  EXPECT_EQ(stats.resimulated_ticks, loop.before_delivery);
  EXPECT_EQ(loop.core.confirmed_world().game_state().get_int("dashes", kOther), 1);
  for (int i = 0; i < 30; ++i) loop.round({0.0, 0.0});
  EXPECT_EQ(loop.core.stats().rollbacks, 1u);
  EXPECT_EQ(loop.core.stats().desyncs, 0u);
}

TEST(RulesPrediction, ThePredictedBroadcastIsReplacedByTheConfirmedOne) {
  RulesLoop loop;
  for (int i = 0; i < 20; ++i) loop.round({0.0, 0.0});
  const std::uint64_t at = loop.sim.current_tick() + loop.lead;
  loop.round({0.0, 0.0}, {"dash"});
  std::vector<server::OutgoingGameMessage> predicted = loop.core.predicted_messages();
  ASSERT_EQ(predicted.size(), 1u);
  EXPECT_EQ(predicted[0].tick, at);
  EXPECT_EQ(predicted[0].client, 0u);
  EXPECT_EQ(predicted[0].payload, "dash 1 1");
  EXPECT_TRUE(loop.server_sent.empty());
  while (loop.core.confirmed_tick() < at) loop.round({0.0, 0.0});
  // Confirmed: no longer a prediction, and the server sent the same message.
  EXPECT_TRUE(loop.core.predicted_messages().empty());
  ASSERT_EQ(loop.server_sent.size(), 1u);
  EXPECT_EQ(loop.server_sent[0].tick, predicted[0].tick);
  EXPECT_EQ(loop.server_sent[0].payload, predicted[0].payload);
}

TEST(RulesPrediction, AMessageFiledLaterThanPredictedRollsBackToTheServersTick) {
  RulesLoop loop;
  for (int i = 0; i < 20; ++i) loop.round({0.0, 0.0});
  // The server files the own message one tick later than the one it names (it came
  // late): the prediction had it a tick early.
  const std::uint64_t local = loop.sim.current_tick() + loop.lead;
  loop.core.send_message(local, "dash");
  loop.sim.submit_game_message(kOwn, local + 1, "dash");
  loop.round({0.0, 0.0});
  while (loop.core.confirmed_tick() < local + 1) loop.round({0.0, 0.0});
  // Two: the tick it was predicted at, and the tick the server filed it at.
  EXPECT_EQ(loop.core.stats().rollbacks, 2u);
  EXPECT_EQ(loop.core.stats().desyncs, 0u);
  EXPECT_EQ(loop.core.confirmed_world().game_state().get_int("dashes", kOwn), 1);
  // A message for a tick already confirmed changes nothing here.
  loop.core.send_message(loop.core.confirmed_tick(), "dash");
  for (int i = 0; i < 15; ++i) loop.round({0.0, 0.0});
  EXPECT_EQ(loop.core.stats().rollbacks, 2u);
  EXPECT_EQ(loop.core.confirmed_world().game_state().get_int("dashes", kOwn), 1);
}

TEST(RulesPrediction, AJoinerIsTakenFromTheRelayAndItsMessagesRunOnItsBody) {
  RulesLoop loop;
  for (int i = 0; i < 10; ++i) loop.round({0.0, 0.0});
  ASSERT_TRUE(loop.sim.leave(kOther));
  const phys::BodyId third = loop.sim.join(3).value();
  loop.sim.submit_game_message(3, loop.sim.current_tick() + 2, "dash");
  for (int i = 0; i < 20; ++i) loop.round({0.0, 0.0});
  EXPECT_EQ(loop.core.stats().desyncs, 0u);
  EXPECT_EQ(loop.core.stats().bad_changes, 0u);
  EXPECT_EQ(loop.core.confirmed_world().game_state().get_int("dashes", 3), 1);
  EXPECT_TRUE(loop.core.confirmed_world().contains(third));
}

TEST(RulesPrediction, ALateJoinersWorldCarriesTheScoreAndTheLastInputSeen) {
  RulesLoop loop;
  for (int i = 0; i < 30; ++i)
    loop.round({2.0, 0.0}, i == 5 ? std::vector<std::string>{"dash"} : std::vector<std::string>{});
  // A second core starts from the server's world as it is now (a Welcome's): the
  // score is in it, and the own input the rules last saw.
  client::PredictionCore late;
  late.set_rules(std::make_shared<DashRules>());
  late.start(phys::World::from_bytes(loop.sim.world().to_bytes()).value(), loop.sim.current_tick(),
             loop.own_body.packed(), loop.sim.tick_rate(), loop.sim.scene().max_acceleration,
             players_of(loop.sim), kOwn);
  EXPECT_EQ(late.predicted_world().game_state().get_int("dashes", kOwn), 1);
  // Sent the same input again, it predicts no new input for the rules, as the server.
  const std::uint64_t next = loop.sim.current_tick() + 1;
  late.set_input(next, {2.0, 0.0});
  late.advance_to(next);
  loop.sim.submit_input(kOwn, next, {2.0, 0.0});
  loop.sim.step_tick();
  physics::wire::Snapshot relay;
  loop.log.append(next - 1, next, loop.log.next_change(), 1,
                  server::RelayLog::Audience::RulesRunners, relay);
  late.on_snapshot(snapshot_of(relay));
  EXPECT_EQ(late.stats().matched_ticks, 1u);
  EXPECT_EQ(late.stats().desyncs, 0u);
}

TEST(RulesPrediction, RelayedMessagesTheRulesCannotHaveAreANamedProblemAndAResync) {
  RulesLoop loop;
  for (int i = 0; i < 10; ++i) loop.round({0.0, 0.0});
  physics::wire::RelayTick forged;
  forged.set_tick(loop.core.confirmed_tick() + 1);
  physics::wire::RelayGameMessage& stranger = *forged.add_messages();
  stranger.set_client_id(99);
  stranger.set_payload("dash");
  client::Snapshot snapshot;
  snapshot.tick = forged.tick();
  snapshot.relay.push_back(forged.SerializeAsString());
  loop.in_flight.clear();
  loop.core.on_snapshot(snapshot);
  EXPECT_EQ(loop.core.stats().bad_changes, 1u);
  EXPECT_TRUE(loop.core.awaiting_full_state());
  EXPECT_NE(loop.core.error().find("99, who is not a player"), std::string::npos)
      << loop.core.error();
  EXPECT_TRUE(loop.core.take_full_state_request());

  // Too many for one tick, from a player.
  client::PredictionCore again;
  again.set_rules(std::make_shared<DashRules>());
  again.start(phys::World::from_bytes(loop.sim.world().to_bytes()).value(), loop.sim.current_tick(),
              loop.own_body.packed(), loop.sim.tick_rate(), 50.0, players_of(loop.sim), kOwn);
  physics::wire::RelayTick flood;
  flood.set_tick(loop.sim.current_tick() + 1);
  for (int i = 0; i < 5; ++i) {
    physics::wire::RelayGameMessage& message = *flood.add_messages();
    message.set_client_id(kOther);
    message.set_payload("dash");
  }
  client::Snapshot flooded;
  flooded.tick = flood.tick();
  flooded.relay.push_back(flood.SerializeAsString());
  again.on_snapshot(flooded);
  EXPECT_EQ(again.stats().bad_changes, 1u);
  EXPECT_NE(again.error().find("for one tick"), std::string::npos) << again.error();
}

TEST(RulesPrediction, RulesThatThrowAskForTheServersWorld) {
  auto throwing = std::make_shared<ThrowingRules>();
  RulesLoop loop(throwing);
  throwing->throw_at = loop.sim.current_tick() + 3;
  for (int i = 0; i < 3; ++i) loop.round({0.0, 0.0});
  EXPECT_EQ(loop.core.stats().rules_errors, 1u);
  EXPECT_TRUE(loop.core.awaiting_full_state());
  EXPECT_NE(loop.core.error().find("threw at tick"), std::string::npos) << loop.core.error();
}

TEST(RulesPrediction, AFullStateWithDamagedGameStateBytesIsRefusedAndAskedAgain) {
  RulesLoop loop;
  for (int i = 0; i < 10; ++i)
    loop.round({0.0, 0.0}, i == 2 ? std::vector<std::string>{"dash"} : std::vector<std::string>{});
  std::vector<std::uint8_t> bytes = loop.sim.world().to_bytes();
  // The game state is written last: damage its final bytes.
  ASSERT_GT(bytes.size(), 8u);
  for (std::size_t i = bytes.size() - 6; i < bytes.size(); ++i) bytes[i] = 0xff;
  client::Snapshot full;
  full.tick = loop.sim.current_tick();
  full.world_state = bytes;
  loop.core.on_snapshot(full);
  EXPECT_EQ(loop.core.stats().bad_world_states, 1u);
  EXPECT_TRUE(loop.core.awaiting_full_state());
  EXPECT_FALSE(loop.core.failed());
}

TEST(RulesPrediction, AServerThatDoesNotRunTheRulesForThisClientIsRefusedAtStart) {
  client::PredictionCore core;
  core.set_rules(std::make_shared<DashRules>());
  server::Simulation sim(dash_scene());
  client::Welcome welcome;
  welcome.tick_rate = 60.0;
  const std::vector<std::uint8_t> bytes = sim.world().to_bytes();
  welcome.world_state.assign(bytes.begin(), bytes.end());
  welcome.rules_run_here = false;
  EXPECT_FALSE(core.start(welcome));
  EXPECT_NE(core.error().find("rules_run_here"), std::string::npos) << core.error();
}

TEST(RulesRelay, RulesRunnersGetMessagesAndInputsAndFollowersGetTheRulesChanges) {
  server::Simulation sim(dash_scene(), {}, std::make_shared<DashRules>());
  server::RelayLog log;
  sim.relay_to(&log);
  sim.join(kOwn);
  sim.submit_game_message(kOwn, 1, "dash");
  sim.submit_input(kOwn, 1, {3.0, 0.0});
  sim.step_tick();
  physics::wire::Snapshot runners;
  physics::wire::Snapshot followers;
  log.append(0, 1, 0, 1, server::RelayLog::Audience::RulesRunners, runners);
  log.append(0, 1, 0, 1, server::RelayLog::Audience::Followers, followers);
  const physics::wire::RelayTick& run = runners.relay(0);
  ASSERT_EQ(run.messages_size(), 1);
  EXPECT_EQ(run.messages(0).client_id(), kOwn);
  EXPECT_EQ(run.messages(0).payload(), "dash");
  ASSERT_EQ(run.rules_inputs_size(), 1);
  EXPECT_EQ(run.rules_inputs(0).ax(), 3.0);
  EXPECT_EQ(run.before_step_size(), 0);
  EXPECT_EQ(run.after_step_size(), 0);
  const physics::wire::RelayTick& follow = followers.relay(0);
  EXPECT_EQ(follow.messages_size(), 0);
  EXPECT_EQ(follow.rules_inputs_size(), 0);
  EXPECT_GT(follow.before_step_size(), 0);  // the dash's velocity
  EXPECT_GT(follow.after_step_size(), 0);   // the game state after the tick
  // Both carry the join, with the player's id.
  ASSERT_EQ(run.joined_size(), 1);
  EXPECT_EQ(run.joined(0).client_id(), kOwn);
  EXPECT_EQ(follow.joined_size(), 1);
}

}  // namespace
