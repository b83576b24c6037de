// The game state through the rules' handle (GameWorld): timers fire at the exact
// tick they were started for, after the tick's inputs and before before_step, in
// (due tick, name, index) order; periodic ones repeat, cancelled ones stop; the
// variables refuse bad values; on_joined learns each player's body; and what the
// rules keep there is in the world's bytes and hash, and reaches the relay's
// followers.
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physics/world.h"
#include "relay/follow_relay.h"
#include "server/game_rules.h"
#include "server/relay_log.h"
#include "server/simulation.h"
#include "test_scene.h"

namespace {

using server::AppliedInput;
using server::ClientId;
using server::GameRules;
using server::GameWorld;
using server::Simulation;

std::string at(const GameWorld& w, const std::string& what) {
  return what + "@" + std::to_string(w.tick());
}

// Timers started at creation and by the timers themselves; each firing written
// down (the log is the test's record, not the game's state).
class TimerRules : public GameRules {
 public:
  std::vector<std::string> log;
  void on_create(GameWorld& w) override {
    ASSERT_TRUE(w.start_timer("once", 5));
    ASSERT_TRUE(w.start_timer("every", 2, 3));
    ASSERT_TRUE(w.start_timer("b", 5));
    ASSERT_TRUE(w.start_timer("a", 5, 0, 7));
    phys::GameStateError error = phys::GameStateError::None;
    EXPECT_FALSE(w.start_timer("now", 0, 0, 0, &error));
    EXPECT_EQ(error, phys::GameStateError::ZeroDelay);
  }
  void on_timer(GameWorld& w, std::string_view name, std::uint64_t index) override {
    log.push_back(at(w, std::string(name) + (index ? " " + std::to_string(index) : "")));
    if (name == "every" && w.tick() == 11) {
      EXPECT_TRUE(w.cancel_timer("every"));
    }
    // A timer started by a timer: one tick on.
    if (name == "once") {
      ASSERT_TRUE(w.start_timer("chained", 1));
    }
    if (name == "chained" && w.tick() == 6) {
      // Started again while running: only the new due tick counts.
      ASSERT_TRUE(w.start_timer("restarted", 2));
      ASSERT_TRUE(w.start_timer("restarted", 4));
    }
    if (const auto body = w.body_of(1)) {
      log.push_back(at(w, "accel " + std::to_string(w.body(*body)->acceleration.x)));
    }
  }
  void before_step(GameWorld& w, const std::vector<AppliedInput>&) override {
    if (w.tick() == 5 || w.tick() == 11) log.push_back(at(w, "before"));
  }
  void after_step(GameWorld& w) override {
    if (w.tick() == 12) {
      ASSERT_TRUE(w.start_timer("from after_step", 3));
    }
  }
};

TEST(GameTimers, FireAtTheirTicksInOrderAfterTheInputsAndRepeat) {
  auto rules = std::make_shared<TimerRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  EXPECT_EQ(sim.world().game_state().timers().size(), 4u);
  ASSERT_TRUE(sim.join(1).has_value());
  sim.submit_input(1, 5, {3.0, 0.0});
  for (int i = 0; i < 20; ++i) sim.step_tick();
  const std::vector<std::string> expected{
      "every@2", "accel 0.000000@2",
      // Tick 5: due at 5, by name then index; the input of tick 5 already applied.
      "a 7@5", "accel 3.000000@5", "b@5", "accel 3.000000@5", "every@5", "accel 3.000000@5",
      "once@5", "accel 3.000000@5", "before@5", "chained@6", "accel 3.000000@6", "every@8",
      "accel 3.000000@8", "restarted@10", "accel 3.000000@10", "every@11", "accel 3.000000@11",
      "before@11", "from after_step@15", "accel 3.000000@15"};
  EXPECT_EQ(rules->log, expected);
  EXPECT_TRUE(sim.world().game_state().timers().empty()) << "once-only timers are gone";
}

class JoinRules : public GameRules {
 public:
  std::vector<std::pair<ClientId, phys::BodyId>> joined;
  server::JoinDecision on_join(GameWorld&, ClientId client, std::optional<std::uint32_t>) override {
    server::JoinDecision decision;
    if (client == 2) {
      phys::BodyDef own;
      own.position = {3.0, 3.0};
      own.name = "own";
      decision.body = own;
    }
    return decision;
  }
  void on_joined(GameWorld& w, ClientId client, phys::BodyId body) override {
    EXPECT_EQ(w.body_of(client), body) << "the player is in the world already";
    joined.emplace_back(client, body);
    ASSERT_TRUE(w.set_int("body", static_cast<std::int64_t>(body.packed()), client));
    ASSERT_TRUE(w.start_timer("welcome", 2, 0, client));
  }
  void on_timer(GameWorld& w, std::string_view, std::uint64_t client) override {
    w.send(static_cast<ClientId>(client), at(w, "welcome"));
  }
};

TEST(GameTimers, OnJoinedLearnsTheBodyAndTimersCountFromTheJoin) {
  auto rules = std::make_shared<JoinRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  const std::optional<phys::BodyId> first = sim.join(1);
  ASSERT_TRUE(first.has_value());
  sim.step_tick();
  const std::optional<phys::BodyId> second = sim.join(2);  // at tick 1
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(sim.world().name(*second), "own");
  ASSERT_EQ(rules->joined.size(), 2u);
  EXPECT_EQ(rules->joined[0], std::make_pair(ClientId{1}, *first));
  EXPECT_EQ(rules->joined[1], std::make_pair(ClientId{2}, *second));
  EXPECT_EQ(sim.world().game_state().get_int("body", 2),
            static_cast<std::int64_t>(second->packed()));
  std::vector<server::OutgoingGameMessage> sent;
  for (int i = 0; i < 4; ++i) {
    sim.step_tick();
    for (auto& m : sim.take_outgoing_messages()) sent.push_back(std::move(m));
  }
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].client, 1u);
  EXPECT_EQ(sent[0].payload, "welcome@2");  // joined at tick 0, after 2 ticks
  EXPECT_EQ(sent[1].client, 2u);
  EXPECT_EQ(sent[1].payload, "welcome@3");  // joined at tick 1
}

// Counts ticks in a game variable and keeps a number beside it.
class CountingRules : public GameRules {
 public:
  void on_create(GameWorld& w) override {
    phys::GameStateError error = phys::GameStateError::None;
    EXPECT_FALSE(w.set_number("heat", std::numeric_limits<double>::quiet_NaN(), 0, &error));
    EXPECT_EQ(error, phys::GameStateError::NotFinite);
    EXPECT_FALSE(w.set_int(std::string(65, 'x'), 1, 0, &error));
    EXPECT_EQ(error, phys::GameStateError::NameTooLong);
    EXPECT_FALSE(w.set_int("", 1));
    EXPECT_TRUE(w.game_state().empty()) << "nothing refused was kept";
    EXPECT_TRUE(w.set_number("heat", 0.5));
    EXPECT_TRUE(w.set_int("gone", 1));
    EXPECT_TRUE(w.erase("gone"));
    EXPECT_FALSE(w.erase("gone"));
  }
  void after_step(GameWorld& w) override {
    w.set_int("ticks", w.get_int("ticks") + 1);
    w.set_number("heat", w.get_number("heat") * 1.5);
  }
};

TEST(GameVariables, RefusedValuesChangeNothingAndKeptOnesAreInTheWorld) {
  Simulation sim(server_test::free_space_scene(), {}, std::make_shared<CountingRules>());
  for (int i = 0; i < 10; ++i) sim.step_tick();
  const phys::GameState& state = sim.world().game_state();
  EXPECT_EQ(state.get_int("ticks"), 10);
  double heat = 0.5;
  for (int i = 0; i < 10; ++i) heat *= 1.5;
  EXPECT_EQ(state.get_number("heat"), heat);
  EXPECT_FALSE(state.get_int("gone").has_value());
  const std::vector<std::uint8_t> bytes = sim.world().to_bytes();
  const std::optional<phys::World> copy = phys::World::from_bytes(bytes);
  ASSERT_TRUE(copy.has_value());
  EXPECT_EQ(copy->game_state().get_int("ticks"), 10);
  EXPECT_EQ(copy->state_hash(), sim.world().state_hash());
  // The same world without the game state hashes otherwise: the state is in the hash.
  phys::World bare(sim.world().save());
  bare.game_state().clear();
  EXPECT_NE(bare.state_hash(), sim.world().state_hash());
}

// A score per player kept by a timer, a join that changes it between ticks, and a
// leave that takes it away: followers of the relay hold the server's game state.
class ScoreRules : public GameRules {
 public:
  void on_create(GameWorld& w) override { w.start_timer("point", 3, 3); }
  void on_joined(GameWorld& w, ClientId client, phys::BodyId) override {
    w.set_int("score", 0, client);
  }
  void on_leave(GameWorld& w, ClientId client) override { w.erase("score", client); }
  void on_timer(GameWorld& w, std::string_view, std::uint64_t) override {
    for (const auto& [client, body] : w.players()) {
      w.set_int("score", w.get_int("score", client) + 1, client);
      w.apply_impulse(body, {0.0, 1.0});
    }
  }
};

// Everything the relay holds from `after` on, followed by `world`; false on a problem.
void follow_log(const server::RelayLog& log, std::uint64_t after, std::uint64_t up_to,
                std::uint64_t first_change, double dt, phys::World& world) {
  physics::wire::Snapshot snapshot;
  log.append(after, up_to, first_change, 1, server::RelayLog::Audience::Followers, snapshot);
  for (const physics::wire::RelayTick& tick : snapshot.relay()) {
    const relay::FollowResult result = relay::follow(world, tick, dt);
    ASSERT_EQ(result.problem, relay::FollowProblem::None) << result.detail;
    ASSERT_TRUE(result.hash_checked);
  }
}

TEST(GameStateInTheRelay, FollowersHoldTheGameStateAndItsHash) {
  Simulation sim(server_test::free_space_scene(), {}, std::make_shared<ScoreRules>());
  server::RelayLog log;
  sim.relay_to(&log);
  ASSERT_TRUE(sim.join(1).has_value());
  std::optional<phys::World> early = phys::World::from_bytes(sim.world().to_bytes());
  ASSERT_TRUE(early.has_value());
  const std::uint64_t early_change = log.next_change();
  for (int i = 0; i < 10; ++i) sim.step_tick();
  follow_log(log, 0, sim.current_tick(), early_change, sim.dt(), *early);
  ASSERT_EQ(sim.world().game_state().get_int("score", 1), 3);
  EXPECT_EQ(early->game_state(), sim.world().game_state());
  // A join between ticks changes the state; a follower welcomed after it, and one
  // that was there before, both end each tick with the server's.
  const std::uint64_t before_join = sim.current_tick();
  ASSERT_TRUE(sim.join(2).has_value());
  std::optional<phys::World> late = phys::World::from_bytes(sim.world().to_bytes());
  ASSERT_TRUE(late.has_value());
  const std::uint64_t late_change = log.next_change();
  ASSERT_TRUE(sim.leave(2));  // and back to the state the relay was last given
  for (int i = 0; i < 10; ++i) sim.step_tick();
  follow_log(log, before_join, sim.current_tick(), early_change, sim.dt(), *early);
  follow_log(log, before_join, sim.current_tick(), late_change, sim.dt(), *late);
  EXPECT_EQ(sim.world().game_state().get_int("score", 1), 6);
  EXPECT_FALSE(sim.world().game_state().get_int("score", 2).has_value());
  EXPECT_EQ(early->game_state(), sim.world().game_state());
  EXPECT_EQ(late->game_state(), sim.world().game_state());
  EXPECT_EQ(late->state_hash(), sim.world().state_hash());
}

TEST(GameStateInTheRelay, AGameStateThatIsNotOneIsRefused) {
  phys::World world;
  physics::wire::RelayTick tick;
  tick.set_tick(1);
  tick.add_after_step()->set_game_state(std::string("\x05\0\0\0\0\0\0\0", 8));
  const relay::FollowResult result = relay::apply_after_step(world, tick);
  EXPECT_EQ(result.problem, relay::FollowProblem::BadInput);
  EXPECT_NE(result.detail.find("game state that is not one"), std::string::npos) << result.detail;
  EXPECT_TRUE(world.game_state().empty());
}

}  // namespace
