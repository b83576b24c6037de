// Game rules on the server (server/game_rules.h), socket-free: each callback at its
// documented point, in order, once a tick; what the rules change happens to the
// world and reaches snapshots and the input relay; players refused or given a body
// of the game's choosing; a rule that throws fails the tick; the world's body limit
// answers rules that create without bound.
#include "server/game_rules.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "relay/follow_relay.h"
#include "server/relay_log.h"
#include "server/simulation.h"
#include "test_scene.h"

namespace {

using server::AppliedInput;
using server::ClientId;
using server::GameRules;
using server::GameWorld;
using server::JoinDecision;
using server::Simulation;

// Writes down every call, with the tick the handle gives.
class RecordingRules : public GameRules {
 public:
  std::vector<std::string> calls;
  void on_create(GameWorld& w) override { calls.push_back("create@" + std::to_string(w.tick())); }
  JoinDecision on_join(GameWorld& w, ClientId client, std::optional<std::uint32_t>) override {
    calls.push_back("join " + std::to_string(client) + "@" + std::to_string(w.tick()));
    return {};
  }
  void on_leave(GameWorld& w, ClientId client) override {
    calls.push_back("leave " + std::to_string(client) + "@" + std::to_string(w.tick()) +
                    (w.body_of(client) ? " with body" : ""));
  }
  void before_step(GameWorld& w, const std::vector<AppliedInput>& inputs) override {
    calls.push_back("before@" + std::to_string(w.tick()) + " inputs " +
                    std::to_string(inputs.size()));
  }
  void after_step(GameWorld& w) override { calls.push_back("after@" + std::to_string(w.tick())); }
  void on_end(GameWorld& w) override { calls.push_back("end@" + std::to_string(w.tick())); }
};

TEST(GameRules, EachCallbackAtItsPointInOrderOnceATick) {
  auto rules = std::make_shared<RecordingRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  ASSERT_TRUE(sim.join(1).has_value());
  sim.submit_input(1, 1, {1.0, 0.0});
  sim.step_tick();
  sim.step_tick();
  ASSERT_TRUE(sim.leave(1));
  sim.step_tick();
  sim.end();
  sim.end();  // once
  EXPECT_EQ(rules->calls,
            (std::vector<std::string>{"create@0", "join 1@0", "before@1 inputs 1", "after@1",
                                      "before@2 inputs 0", "after@2", "leave 1@2",
                                      "before@3 inputs 0", "after@3", "end@3"}));
}

// Spawns a box at tick 2, teleports it at 3, pushes it at 4 and destroys it at 5,
// before each step; then makes another.
class BoxRules : public GameRules {
 public:
  phys::BodyId box;
  phys::BodyId second;
  void before_step(GameWorld& w, const std::vector<AppliedInput>&) override {
    phys::BodyDef def;
    def.shape = phys::Shape::Box;
    def.position = {-20.0, 0.0};
    def.mass = 2.0;
    switch (w.tick()) {
      case 2:
        box = w.create(def);
        break;
      case 3:
        EXPECT_TRUE(w.set_position(box, {-30.0, 5.0}));
        break;
      case 4:
        EXPECT_TRUE(w.apply_impulse(box, {4.0, -2.0}));  // 2 kg: (2, -1) m/s
        break;
      case 5:
        EXPECT_TRUE(w.destroy(box));
        EXPECT_FALSE(w.destroy(box));
        second = w.create(def);
        break;
      default:
        break;
    }
  }
};

TEST(GameRules, WhatTheRulesChangeHappensAndReachesSnapshots) {
  auto rules = std::make_shared<BoxRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  sim.step_tick();
  sim.take_changes();
  sim.step_tick();  // 2: made
  ASSERT_TRUE(rules->box.is_valid());
  EXPECT_EQ(sim.take_changes().added, std::vector<phys::BodyId>{rules->box});
  sim.step_tick();  // 3: teleported (free space: no gravity, no friction)
  EXPECT_EQ(sim.world().body(rules->box)->position, (phys::Vec2{-30.0, 5.0}));
  sim.step_tick();  // 4: pushed
  EXPECT_EQ(sim.world().body(rules->box)->velocity, (phys::Vec2{2.0, -1.0}));
  sim.take_changes();
  sim.step_tick();  // 5: gone, and another made in its slot with a new generation
  EXPECT_FALSE(sim.world().contains(rules->box));
  ASSERT_TRUE(rules->second.is_valid());
  EXPECT_NE(rules->second, rules->box);
  EXPECT_EQ(rules->second.index, rules->box.index);
  const server::BodyChanges changes = sim.take_changes();
  EXPECT_EQ(changes.removed, std::vector<std::uint64_t>{rules->box.packed()});
  EXPECT_EQ(changes.added, std::vector<phys::BodyId>{rules->second});
}

// A player's own body cannot be taken away by the rules; the player leaves instead.
class GreedyRules : public GameRules {
 public:
  bool destroyed_player = true;
  void before_step(GameWorld& w, const std::vector<AppliedInput>& inputs) override {
    for (const AppliedInput& input : inputs) destroyed_player = w.destroy(input.body);
  }
};

TEST(GameRules, APlayersBodyIsNotTheRulesToDestroy) {
  auto rules = std::make_shared<GreedyRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  ASSERT_TRUE(sim.join(1).has_value());
  sim.submit_input(1, 1, {0.0, 1.0});
  sim.step_tick();
  EXPECT_FALSE(rules->destroyed_player);
  EXPECT_TRUE(sim.world().contains(*sim.body_of(1)));
}

// Odd clients are refused; even ones get a big box instead of the scene's circle.
class DoorRules : public GameRules {
 public:
  JoinDecision on_join(GameWorld&, ClientId client, std::optional<std::uint32_t>) override {
    JoinDecision decision;
    if (client % 2 == 1) {
      decision.refuse = "odd players wait for the next round";
      return decision;
    }
    phys::BodyDef def;
    def.shape = phys::Shape::Box;
    def.half_extents = {1.5, 0.5};
    def.position = {5.0 * client, 40.0};
    def.mass = 3.0;
    decision.body = def;
    return decision;
  }
};

TEST(GameRules, OnJoinRefusesAPlayerOrChoosesItsBody) {
  Simulation sim(server_test::free_space_scene(), {}, std::make_shared<DoorRules>());
  const server::Admission refused = sim.admit(1);
  EXPECT_FALSE(refused.body.has_value());
  EXPECT_EQ(refused.refused, "odd players wait for the next round");
  EXPECT_FALSE(sim.room().contains(1));
  const server::Admission admitted = sim.admit(2);
  ASSERT_TRUE(admitted.body.has_value());
  const auto body = sim.world().body(*admitted.body);
  EXPECT_EQ(body->shape, phys::Shape::Box);
  EXPECT_EQ(body->half_extents, (phys::Vec2{1.5, 0.5}));
  EXPECT_EQ(body->position, (phys::Vec2{10.0, 40.0}));
  EXPECT_EQ(body->mass, 3.0);
}

class ThrowingRules : public GameRules {
 public:
  void after_step(GameWorld& w) override {
    if (w.tick() == 3) throw std::runtime_error("the rules failed on purpose");
  }
};

TEST(GameRules, ARuleThatThrowsFailsTheTick) {
  Simulation sim(server_test::free_space_scene(), {}, std::make_shared<ThrowingRules>());
  sim.step_tick();
  sim.step_tick();
  EXPECT_THROW(sim.step_tick(), std::runtime_error);
}

// Creates a body every tick, without end: the world's body limit answers.
class FloodRules : public GameRules {
 public:
  std::size_t made = 0;
  std::size_t refused = 0;
  void before_step(GameWorld& w, const std::vector<AppliedInput>&) override {
    for (int i = 0; i < 100; ++i) {
      phys::BodyDef def;
      def.shape = phys::Shape::Circle;
      def.radius = 0.1;
      def.position = {static_cast<double>(made % 1000), static_cast<double>(made / 1000) + 50.0};
      phys::BodyDefError error{};
      if (w.create(def, &error).is_valid()) {
        ++made;
      } else {
        EXPECT_EQ(error, phys::BodyDefError::TooManyBodies);
        ++refused;
      }
    }
  }
};

TEST(GameRules, RulesThatCreateWithoutBoundMeetTheWorldsBodyLimit) {
  scene::SceneDef scene = server_test::free_space_scene();
  scene.world.max_bodies = 250;
  auto rules = std::make_shared<FloodRules>();
  Simulation sim(scene, {}, rules);
  for (int i = 0; i < 5; ++i) sim.step_tick();
  EXPECT_EQ(rules->made, 250u);
  EXPECT_EQ(rules->refused, 250u);
  EXPECT_EQ(sim.world().body_count(), 250u);
}

// Everything the rules do, followed through the input relay: a client's world holds
// the server's bit for bit, tick by tick (docs/PROTOCOL.md 5.12).
class BusyRules : public GameRules {
 public:
  std::vector<phys::BodyId> made;
  void before_step(GameWorld& w, const std::vector<AppliedInput>&) override {
    if (w.tick() % 7 == 0) {
      phys::BodyDef def;
      def.shape = w.tick() % 2 ? phys::Shape::Circle : phys::Shape::Box;
      def.position = {-15.0 + static_cast<double>(w.tick() % 11), 3.0};
      def.velocity = {1.0, -0.5};
      made.push_back(w.create(def));
    }
    if (w.tick() % 5 == 0 && !made.empty()) w.apply_impulse(made.front(), {0.5, 0.25});
  }
  void after_step(GameWorld& w) override {
    if (w.tick() % 13 == 0 && made.size() > 1) {
      w.destroy(made.back());
      made.pop_back();
    }
    if (w.tick() % 9 == 0 && !made.empty()) w.set_position(made.front(), {-12.0, 1.0});
  }
};

TEST(GameRules, TheRelayCarriesWhatTheRulesDid) {
  auto rules = std::make_shared<BusyRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  server::RelayLog log;
  sim.relay_to(&log);
  ASSERT_TRUE(sim.join(1).has_value());
  const std::vector<std::uint8_t> bytes = sim.world().to_bytes();
  std::optional<phys::World> follower = phys::World::from_bytes(bytes);
  ASSERT_TRUE(follower.has_value());
  std::uint64_t sent = sim.current_tick();
  const std::uint64_t first_change = log.next_change();
  for (int i = 0; i < 120; ++i) {
    sim.submit_input(1, sim.current_tick() + 1, {std::sin(i * 0.1), 1.0});
    sim.step_tick();
    physics::wire::Snapshot snapshot;
    log.append(sent, sim.current_tick(), first_change, 1, server::RelayLog::Audience::Followers,
               snapshot);
    sent = sim.current_tick();
    for (const physics::wire::RelayTick& tick : snapshot.relay()) {
      const relay::FollowResult result = relay::follow(*follower, tick, sim.dt());
      ASSERT_EQ(result.problem, relay::FollowProblem::None) << result.detail;
      ASSERT_TRUE(result.hash_checked);
    }
    ASSERT_EQ(follower->state_hash(), sim.world().state_hash()) << "tick " << sim.current_tick();
  }
  EXPECT_GT(rules->made.size(), 5u);
}

// Writes down the game messages each tick delivers.
class MailRules : public GameRules {
 public:
  std::vector<std::string> seen;
  void before_step(GameWorld& w, const std::vector<AppliedInput>&) override {
    for (const server::ClientGameMessage& m : w.messages()) {
      seen.push_back(std::to_string(w.tick()) + ":" + std::to_string(m.client) + ":" + m.payload);
    }
  }
};

TEST(GameMessages, DeliveredOnTheirTickAndEveryLimitAnswered) {
  auto rules = std::make_shared<MailRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  ASSERT_TRUE(sim.join(1).has_value());
  ASSERT_TRUE(sim.join(2).has_value());
  using V = server::GameMessageVerdict;
  EXPECT_EQ(sim.submit_game_message(2, 3, "b"), V::OnTime);
  EXPECT_EQ(sim.submit_game_message(1, 3, "a1"), V::OnTime);
  EXPECT_EQ(sim.submit_game_message(1, 3, "a2"), V::OnTime);
  EXPECT_EQ(sim.submit_game_message(1, 3, "a3"), V::OnTime);
  EXPECT_EQ(sim.submit_game_message(1, 3, "a4"), V::OnTime);
  EXPECT_EQ(sim.submit_game_message(1, 3, "a5"), V::TooMany);
  EXPECT_EQ(sim.submit_game_message(1, 2, std::string(server::kMaxGameMessageBytes + 1, 'x')),
            V::TooLarge);
  EXPECT_EQ(sim.submit_game_message(1, 2, std::string(server::kMaxGameMessageBytes, 'x')),
            V::OnTime);
  EXPECT_EQ(sim.submit_game_message(1, sim.max_ticks_ahead() + 1, "far"), V::TooFarAhead);
  EXPECT_EQ(sim.submit_game_message(7, 2, "stranger"), V::NotJoined);
  for (int i = 0; i < 3; ++i) sim.step_tick();
  EXPECT_EQ(sim.submit_game_message(2, 1, "late"), V::Late);  // tick 1 has passed: at 4
  sim.step_tick();
  EXPECT_EQ(rules->seen,
            (std::vector<std::string>{"2:1:" + std::string(256, 'x'), "3:1:a1", "3:1:a2", "3:1:a3",
                                      "3:1:a4", "3:2:b", "4:2:late"}));
  // Without rules a message has nowhere to go.
  Simulation plain(server_test::free_space_scene());
  ASSERT_TRUE(plain.join(1).has_value());
  EXPECT_EQ(plain.submit_game_message(1, 1, "x"), V::NoGame);
}

// The rules' own messages: to one player or all, stamped with the tick.
class HeraldRules : public GameRules {
 public:
  void after_step(GameWorld& w) override {
    if (w.tick() == 2) {
      EXPECT_TRUE(w.send(1, "to one"));
    }
    if (w.tick() == 3) {
      EXPECT_TRUE(w.broadcast("to all"));
      EXPECT_FALSE(w.broadcast(std::string(server::kMaxOutgoingGameMessageBytes + 1, 'y')));
    }
  }
};

TEST(GameMessages, TheRulesSendToOneOrAll) {
  Simulation sim(server_test::free_space_scene(), {}, std::make_shared<HeraldRules>());
  ASSERT_TRUE(sim.join(1).has_value());
  for (int i = 0; i < 3; ++i) sim.step_tick();
  const std::vector<server::OutgoingGameMessage> out = sim.take_outgoing_messages();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].client, 1u);
  EXPECT_EQ(out[0].tick, 2u);
  EXPECT_EQ(out[0].payload, "to one");
  EXPECT_EQ(out[1].client, 0u);
  EXPECT_EQ(out[1].tick, 3u);
  EXPECT_TRUE(sim.take_outgoing_messages().empty());
}

// A goal: a named sensor the rules find by name, and a ball sent through it; the
// rules see it enter and leave at the steps it does.
class GoalRules : public GameRules {
 public:
  std::vector<std::string> seen;
  void on_create(GameWorld& w) override {
    phys::BodyDef goal;
    goal.shape = phys::Shape::Box;
    goal.motion = phys::Motion::Static;
    goal.is_sensor = true;
    goal.name = "goal";
    goal.position = {5.0, 0.0};
    goal.half_extents = {1.0, 1.0};
    w.create(goal);
    phys::BodyDef ball;
    ball.shape = phys::Shape::Circle;
    ball.radius = 0.25;
    ball.position = {0.0, 0.0};
    ball.velocity = {6.0, 0.0};  // 0.1 m a tick
    ball.name = "ball";
    w.create(ball);
  }
  void after_step(GameWorld& w) override {
    const auto goal = w.find_body("goal");
    for (const phys::SensorEvent& e : w.sensor_events()) {
      EXPECT_EQ(e.sensor, *goal);
      seen.push_back((e.kind == phys::SensorEventKind::Begin ? "in@" : "out@") +
                     std::to_string(w.tick()));
    }
  }
};

TEST(GameRules, TheRulesFindBodiesByNameAndSeeSensorEvents) {
  auto rules = std::make_shared<GoalRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  for (int i = 0; i < 80; ++i) sim.step_tick();
  // Its right edge 0.1 n + 0.25 passes the goal's left side (4) at tick 38; its
  // left edge 0.1 n - 0.25 reaches the goal's right side (6) at tick 63.
  EXPECT_EQ(rules->seen, (std::vector<std::string>{"in@38", "out@63"}));
}

}  // namespace

// A sweeper: a kinematic wall driving a ball into a static wall; the rules see the
// crush (the three bodies) on the tick the gap closes below the ball's width, and
// destroy the ball, after which nothing is crushed.
class CrushRules : public GameRules {
 public:
  phys::BodyId sweeper, ball, wall;
  std::vector<std::uint64_t> crushed_at;
  double front_when_crushed = 0.0;
  void on_create(GameWorld& w) override {
    phys::BodyDef def;
    def.shape = phys::Shape::Box;
    def.motion = phys::Motion::Static;
    def.position = {5.25, 0.0};
    def.half_extents = {0.25, 2.0};
    wall = w.create(def);  // near face at x = 5
    def.motion = phys::Motion::Kinematic;
    def.position = {0.0, 0.0};
    def.half_extents = {0.5, 2.0};
    def.velocity = {3.0, 0.0};  // 0.05 m a tick
    sweeper = w.create(def);
    phys::BodyDef ball_def;
    ball_def.shape = phys::Shape::Circle;
    ball_def.radius = 0.5;
    ball_def.position = {2.0, 0.0};
    ball = w.create(ball_def);
  }
  void after_step(GameWorld& w) override {
    for (const phys::CrushEvent& e : w.crush_events()) {
      EXPECT_EQ(e.kinematic, sweeper);
      EXPECT_EQ(e.dynamic, ball);
      EXPECT_EQ(e.fixed, wall);
      if (crushed_at.empty()) front_when_crushed = w.body(sweeper)->position.x + 0.5;
      crushed_at.push_back(w.tick());
      w.destroy(e.dynamic);
    }
  }
};

TEST(GameRules, TheRulesSeeABodyCrushedBetweenAKinematicAndAStaticBody) {
  auto rules = std::make_shared<CrushRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  for (int i = 0; i < 90; ++i) sim.step_tick();
  // The gap (5 - the sweeper's front) closes below the ball's width (1) when the
  // front passes 4, 7/6 s in; the crush comes within a tick of it, once.
  ASSERT_EQ(rules->crushed_at.size(), 1u);
  EXPECT_GT(rules->front_when_crushed, 4.0);
  EXPECT_LE(rules->front_when_crushed, 4.0 + 0.05 + 1e-9);
}
