// The game state in the world, as a game's tests meet it: check_rules_state_in_world
// catches rules that keep a counter or a cached id in a member and passes rules
// that keep them in game variables; GameRun places, moves and removes bodies between
// ticks; a late joiner's Welcome.world_state holds the score; and
// compare_lockstep_run holds a networked lockstep game to the in-process one.
#include "physics_testing/rules_state_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <string>

#include "physics_testing/clients.h"
#include "physics_testing/game_run.h"
#include "physics_testing/in_process_server.h"
#include "physics_testing/lockstep_check.h"

namespace physics_testing {
namespace {

using namespace std::chrono_literals;

// Every 10th tick of its own count, a kick to every player and a message: the count
// in a member, which a fresh rules object starts again from 0.
class MemberCounter : public server::GameRules {
 public:
  void after_step(server::GameWorld& w) override {
    if (++ticks_ % 10 != 0) return;
    for (const auto& [client, body] : w.players()) w.apply_impulse(body, {0.0, 2.0});
    w.broadcast("kick " + std::to_string(ticks_));
  }

 private:
  std::int64_t ticks_ = 0;
};

// The same game with the count in a game variable.
class WorldCounter : public server::GameRules {
 public:
  void after_step(server::GameWorld& w) override {
    const std::int64_t ticks = w.get_int("ticks") + 1;
    w.set_int("ticks", ticks);
    if (ticks % 10 != 0) return;
    for (const auto& [client, body] : w.players()) w.apply_impulse(body, {0.0, 2.0});
    w.broadcast("kick " + std::to_string(ticks));
  }
};

// The same with a timer, which also keeps its count.
class TimerCounter : public server::GameRules {
 public:
  void on_create(server::GameWorld& w) override { w.start_timer("kick", 10, 10); }
  void on_timer(server::GameWorld& w, std::string_view, std::uint64_t) override {
    w.set_int("kicks", w.get_int("kicks") + 1);
    for (const auto& [client, body] : w.players()) w.apply_impulse(body, {0.0, 2.0});
    w.broadcast("kick " + std::to_string(w.get_int("kicks")));
  }
};

// A body found once, at creation, and pushed every tick: the id kept in a member.
class CachedId : public server::GameRules {
 public:
  void on_create(server::GameWorld& w) override {
    phys::BodyDef crate;
    crate.position = {0.0, 6.0};
    crate.name = "crate";
    crate_ = w.create(crate);
  }
  void before_step(server::GameWorld& w, const std::vector<server::AppliedInput>&) override {
    w.set_velocity(crate_, {1.0, 0.0});
  }

 private:
  phys::BodyId crate_;
};

template <class Rules>
RulesFactory factory() {
  return [] { return std::make_shared<Rules>(); };
}

// Two players, who steer and join at ticks 1 and 4.
void two_players(GameRun& run, std::uint64_t tick) {
  if (tick == 1 || tick == 4) {
    ASSERT_TRUE(run.join());
  }
  for (const auto& [client, body] : run.simulation().room().members()) {
    ASSERT_TRUE(run.input(client, std::sin(static_cast<double>(tick) * 0.3) * 5.0, 0.0));
  }
}

TEST(CheckRulesStateInWorld, RulesThatKeepTheirStateInTheWorldPass) {
  for (const RulesFactory& rules : {factory<WorldCounter>(), factory<TimerCounter>()}) {
    const Expected<RulesStateCheck> check =
        check_rules_state_in_world(scene::default_scene(), rules, two_players, 60);
    ASSERT_TRUE(check) << check.message();
    EXPECT_EQ(check->hashes.size(), 60u);
    EXPECT_EQ(check->messages, 6u);
    EXPECT_GT(std::set<std::uint64_t>(check->hashes.begin(), check->hashes.end()).size(), 50u);
  }
}

TEST(CheckRulesStateInWorld, ACounterInAMemberIsCaughtAtTheFirstTickItShows) {
  const Expected<RulesStateCheck> check =
      check_rules_state_in_world(scene::default_scene(), factory<MemberCounter>(), two_players, 60);
  ASSERT_FALSE(check);
  // Tick 10: the kick changes the players' bodies (the hash shows it first).
  EXPECT_NE(check.message().find("tick 10: the state hash is 0x"), std::string::npos)
      << check.message();
  EXPECT_NE(check.message().find("outside the world"), std::string::npos) << check.message();
}

TEST(CheckRulesStateInWorld, AMessageFromAMemberIsCaughtToo) {
  // No players: nothing to kick, so only the message tells the runs apart.
  const Expected<RulesStateCheck> check = check_rules_state_in_world(
      scene::default_scene(), factory<MemberCounter>(), [](GameRun&, std::uint64_t) {}, 30);
  ASSERT_FALSE(check);
  EXPECT_NE(check.message().find("tick 10: the rules sent 1 messages with one rules object and 0"),
            std::string::npos)
      << check.message();
}

TEST(CheckRulesStateInWorld, AnIdCachedAtCreationIsCaught) {
  const Expected<RulesStateCheck> check = check_rules_state_in_world(
      scene::default_scene(), factory<CachedId>(), [](GameRun&, std::uint64_t) {}, 5);
  ASSERT_FALSE(check);
  EXPECT_NE(check.message().find("tick 1: the state hash"), std::string::npos) << check.message();
}

TEST(GameRunEdits, BodiesArePlacedMovedAndRemovedBetweenTicks) {
  GameRun run(scene::default_scene(), std::make_shared<WorldCounter>());
  const auto player = run.join();
  ASSERT_TRUE(player);
  phys::BodyDef crate;
  crate.position = {2.0, 5.0};
  crate.name = "placed";
  const Expected<phys::BodyId> placed = run.add_body(crate);
  ASSERT_TRUE(placed) << placed.message();
  EXPECT_EQ(run.simulation().take_changes().added.back(), *placed) << "for the snapshots";
  ASSERT_TRUE(run.set_position(*placed, -1.0, 7.0));
  ASSERT_TRUE(run.set_velocity(*placed, 3.0, 0.0));
  EXPECT_EQ(run.body("placed")->position, (phys::Vec2{-1.0, 7.0}));
  run.step();
  EXPECT_GT(run.body("placed")->position.x, -1.0) << "it moved with the velocity set";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(run.set_position(*placed, nan, 0.0));
  crate.position = {nan, 0.0};
  const Expected<phys::BodyId> refused = run.add_body(crate);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("refused"), std::string::npos) << refused.message();
  EXPECT_FALSE(run.remove_body(*run.body_of(*player))) << "a player's body leaves with it";
  ASSERT_TRUE(run.remove_body(*placed));
  EXPECT_FALSE(run.body("placed"));
  EXPECT_FALSE(run.remove_body(*placed));
  EXPECT_EQ(run.game_state().get_int("ticks"), 1);
}

TEST(GameStateOverTheNetwork, ALateJoinersWorldHoldsTheScore) {
  server::ServerConfig config = test_server_config();
  config.rules = std::make_shared<WorldCounter>();
  InProcessServer server(scene::default_scene(), config);
  auto first = std::make_unique<client::Client>(server.client_config("first"));
  ASSERT_TRUE(first->connect(10s)) << first->last_error().to_string();
  ASSERT_TRUE(wait_for_snapshot(
      *first, [](const client::Snapshot& s) { return s.tick >= 30; }, 10s, "tick 30"));
  client::ClientConfig late_config = server.client_config("late");
  late_config.want_world = true;
  client::Client late(late_config);
  ASSERT_TRUE(late.connect(10s)) << late.last_error().to_string();
  const client::Welcome& welcome = late.welcome();
  std::string error;
  const std::optional<phys::World> world = phys::World::from_bytes(welcome.world_state, &error);
  ASSERT_TRUE(world.has_value()) << error;
  // The rules count every tick stepped: the world it was sent is that of current_tick.
  EXPECT_GE(welcome.current_tick, 30u);
  EXPECT_EQ(world->game_state().get_int("ticks"), static_cast<std::int64_t>(welcome.current_tick));
}

server::ServerConfig lockstep_game_config(std::shared_ptr<server::GameRules> rules) {
  server::ServerConfig config = test_server_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;  // no tick may be stepped without every input
  config.rules = std::move(rules);
  return config;
}

client::Vec2 steering(std::size_t k, std::uint64_t t) {
  const double phase = static_cast<double>(t) * 0.17 + static_cast<double>(k);
  return {6.0 * std::cos(phase), 0.0};
}

TEST(CompareLockstepRunWithRules, AGameOverTheNetworkMatchesTheInProcessGame) {
  const scene::SceneDef scene = scene::default_scene();
  InProcessServer server(scene, lockstep_game_config(std::make_shared<TimerCounter>()));
  Expected<Clients> players = connect_clients(server.exact_client_config("p"), 2);
  ASSERT_TRUE(players);
  const Expected<LockstepRun> run =
      compare_lockstep_run(scene, factory<TimerCounter>(), *players, steering, 45);
  ASSERT_TRUE(run) << run.message();
  EXPECT_EQ(run->hashes.size(), 45u);
}

TEST(CompareLockstepRunWithRules, OtherRulesAreCaughtAtTheFirstTickTheyDiffer) {
  const scene::SceneDef scene = scene::default_scene();
  InProcessServer server(scene, lockstep_game_config(std::make_shared<TimerCounter>()));
  Expected<Clients> players = connect_clients(server.exact_client_config("p"), 2);
  ASSERT_TRUE(players);
  // No rules in-process: the same physics until the first kick's tick.
  const Expected<LockstepRun> run = compare_lockstep_run(
      scene, [] { return std::make_shared<server::GameRules>(); }, *players, steering, 45);
  ASSERT_FALSE(run);
  EXPECT_NE(run.message().find("differs from the in-process world's"), std::string::npos)
      << run.message();
}

}  // namespace
}  // namespace physics_testing
