// Goal rush's rules, tested as a game team would: the rules on the server's own tick
// logic in-process (physics_testing::GameRun), then the real server over loopback.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "goal_rush_rules.h"
#include "physics_testing/testing.h"

namespace {

using namespace std::chrono_literals;
using goal_rush::GoalRushRules;
using goal_rush::Side;
using physics_testing::GameRun;

scene::SceneDef goal_rush_scene() {
  auto scene = physics_testing::load_scene(GOAL_RUSH_SCENE);
  if (!scene) throw std::runtime_error(scene.message());
  return *scene;
}

// The rules, with a hand of the test's own before the tick's own rules: where a test
// puts the ball. (A game's own debug commands would come in as game messages.)
class ScriptedRules : public GoalRushRules {
 public:
  using GoalRushRules::GoalRushRules;
  std::function<void(server::GameWorld&)> before_next_tick;
  void before_step(server::GameWorld& world,
                   const std::vector<server::AppliedInput>& inputs) override {
    if (before_next_tick) std::exchange(before_next_tick, nullptr)(world);
    GoalRushRules::before_step(world, inputs);
  }
};

struct Game {
  scene::SceneDef scene = goal_rush_scene();
  std::shared_ptr<ScriptedRules> rules = std::make_shared<ScriptedRules>(scene.player);
  GameRun run{scene, rules};
};

// Drops the ball above a goal and steps until the tick that scored (at most 2 s).
// The tick's record, or nullptr if no goal came.
const physics_testing::GameTick* drop_ball_into(Game& game, std::string_view goal) {
  const phys::Vec2 above{goal == "left goal" ? -14.0 : 14.0, 5.0};
  game.rules->before_next_tick = [above](server::GameWorld& world) {
    const phys::BodyId ball = *world.find_body("ball");
    world.set_position(ball, above);
    world.set_velocity(ball, {0.0, 0.0});
  };
  for (int i = 0; i < 120; ++i) {
    const physics_testing::GameTick& tick = game.run.step();
    if (!tick.messages.empty()) return &tick;
  }
  return nullptr;
}

bool contact_between(const physics_testing::GameTick& tick, phys::BodyId a, phys::BodyId b) {
  return std::any_of(tick.contact_events.begin(), tick.contact_events.end(),
                     [&](const phys::ContactEvent& event) {
                       return (event.a == a && event.b == b) || (event.a == b && event.b == a);
                     });
}

TEST(GoalRush, TwoPlayersJoinAndAThirdIsRefused) {
  Game game;
  const auto left = game.run.join();
  const auto right = game.run.join();
  ASSERT_TRUE(left);
  ASSERT_TRUE(right);
  EXPECT_EQ(GoalRushRules::side_of(game.run.world(), *left), Side::Left);
  EXPECT_EQ(GoalRushRules::side_of(game.run.world(), *right), Side::Right);
  EXPECT_TRUE(game.run.body("left player"));
  EXPECT_TRUE(game.run.body("right player"));
  const auto third = game.run.join();
  ASSERT_FALSE(third);
  EXPECT_NE(third.message().find("the game is full"), std::string::npos) << third.message();
  // A seat freed is a seat taken again.
  ASSERT_TRUE(game.run.leave(*left));
  EXPECT_TRUE(game.run.join());
}

TEST(GoalRush, TheBallInAGoalScoresForTheOtherSideAndComesBack) {
  Game game;
  const physics_testing::GameTick* goal = drop_ball_into(game, "left goal");
  ASSERT_NE(goal, nullptr) << "no goal in 2 s";
  EXPECT_EQ(GoalRushRules::score(game.run.world(), Side::Right), 1);
  EXPECT_EQ(GoalRushRules::score(game.run.world(), Side::Left), 0);
  ASSERT_EQ(goal->messages.size(), 1u);
  EXPECT_EQ(goal->messages[0].payload, "score 0 1");
  EXPECT_EQ(goal->messages[0].client, 0u);  // to everyone
  // The sensor saw the ball begin to overlap at that very tick.
  const phys::BodyId ball = *game.run.find_body("ball");
  const phys::BodyId left_goal = *game.run.find_body("left goal");
  EXPECT_TRUE(std::any_of(goal->sensor_events.begin(), goal->sensor_events.end(),
                          [&](const phys::SensorEvent& event) {
                            return event.kind == phys::SensorEventKind::Begin &&
                                   event.sensor == left_goal && event.visitor == ball;
                          }));
  // The ball is back at the start, at rest.
  const phys::BodyState after = *game.run.body("ball");
  EXPECT_EQ(after.position, GoalRushRules::kBallStart);
  EXPECT_EQ(after.velocity, (phys::Vec2{0.0, 0.0}));
  // The other goal scores for the other side.
  ASSERT_NE(drop_ball_into(game, "right goal"), nullptr);
  EXPECT_EQ(GoalRushRules::score(game.run.world(), Side::Left), 1);
}

TEST(GoalRush, FiveGoalsWinAndTheScoresStartAgain) {
  Game game;
  for (int goal = 1; goal <= goal_rush::kWinningScore; ++goal) {
    ASSERT_NE(drop_ball_into(game, "right goal"), nullptr) << "goal " << goal;
  }
  const std::vector<std::string> heard = game.run.messages_to(1);
  ASSERT_FALSE(heard.empty());
  EXPECT_EQ(heard.back(), "win left");
  EXPECT_EQ(heard[heard.size() - 2], "score 5 0");
  EXPECT_EQ(GoalRushRules::score(game.run.world(), Side::Left), 0);
}

TEST(GoalRush, AShotNeverTouchesItsOwnPlayer) {
  Game game;
  const auto shooter = game.run.join();
  ASSERT_TRUE(shooter);
  game.run.step(30);  // on the ground
  const phys::BodyId own = *game.run.body_of(*shooter);
  const double x_before = game.run.world().body(own)->position.x;
  ASSERT_TRUE(game.run.message(*shooter, "shoot"));
  game.run.step();
  const std::optional<phys::BodyId> shot = game.run.find_body("shot");
  ASSERT_TRUE(shot) << "no shot was made";
  EXPECT_EQ(GoalRushRules::shots_in_flight(game.run.world()), 1u);
  // It was made inside its player, and flies out of it untouched: no contact, and
  // the player is not pushed.
  const phys::BodyId ground = *game.run.find_body("ground");
  bool hit_the_ground = false;
  for (int i = 0; i < 60; ++i) {
    const physics_testing::GameTick& tick = game.run.step();
    EXPECT_FALSE(contact_between(tick, *shot, own)) << "at tick " << tick.tick;
    hit_the_ground = hit_the_ground || contact_between(tick, *shot, ground);
  }
  EXPECT_NEAR(game.run.world().body(own)->position.x, x_before, 1e-9);
  // A solid body all the same: it meets the ground.
  EXPECT_TRUE(hit_the_ground);
  // Shots expire, and at most three fly at once.
  game.run.step(goal_rush::kShotLifeTicks);
  EXPECT_EQ(GoalRushRules::shots_in_flight(game.run.world()), 0u);
  EXPECT_FALSE(game.run.find_body("shot"));
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(game.run.message(*shooter, "shoot"));
  game.run.step();
  EXPECT_EQ(GoalRushRules::shots_in_flight(game.run.world()), goal_rush::kMaxShotsPerPlayer);
}

TEST(GoalRush, APlayerJumpsFromTheGroundOnly) {
  Game game;
  const auto player = game.run.join();
  ASSERT_TRUE(player);
  game.run.step(30);
  ASSERT_TRUE(game.run.message(*player, "jump"));
  game.run.step();
  const double up = game.run.body("left player")->velocity.y;
  EXPECT_GT(up, 6.0);
  game.run.step(5);
  const double rising = game.run.body("left player")->velocity.y;
  ASSERT_TRUE(game.run.message(*player, "jump"));  // in the air: nothing
  game.run.step();
  EXPECT_LT(game.run.body("left player")->velocity.y, rising);
}

TEST(GoalRush, PlayersRunButDoNotFly) {
  Game game;
  const auto player = game.run.join();
  ASSERT_TRUE(player);
  game.run.step(30);
  const phys::BodyState start = *game.run.body("left player");
  ASSERT_TRUE(game.run.input(*player, 0.0, 30.0));
  game.run.step(60);
  EXPECT_NEAR(game.run.body("left player")->position.y, start.position.y, 1e-3);
  ASSERT_TRUE(game.run.input(*player, 30.0, 30.0));
  game.run.step(60);
  const phys::BodyState ran = *game.run.body("left player");
  EXPECT_GT(ran.position.x, start.position.x + 2.0);
  EXPECT_NEAR(ran.position.y, start.position.y, 1e-3);
}

TEST(GoalRush, ThePlatformKeepsToItsPath) {
  Game game;
  const double slack = goal_rush::kPlatformSpeed / 60.0 + 1e-9;  // one tick past an end
  int turns = 0;
  double last_vx = game.run.body("platform")->velocity.x;
  for (int i = 0; i < 720; ++i) {  // 12 s: out to one end (3 s), to the other (6 s), back
    game.run.step();
    const phys::BodyState platform = *game.run.body("platform");
    ASSERT_LE(std::abs(platform.position.x), goal_rush::kPlatformHalfPath + slack);
    EXPECT_EQ(platform.position.y, 4.0);
    if ((platform.velocity.x > 0.0) != (last_vx > 0.0)) ++turns;
    last_vx = platform.velocity.x;
  }
  EXPECT_EQ(turns, 2);
}

// Puts the ball at `where`, at rest, before the next tick's rules.
void place_ball(Game& game, phys::Vec2 where) {
  game.rules->before_next_tick = [where](server::GameWorld& world) {
    const phys::BodyId ball = *world.find_body("ball");
    world.set_position(ball, where);
    world.set_velocity(ball, {0.0, 0.0});
  };
}

// What the rules told `client` during the tick.
std::vector<std::string> told(const physics_testing::GameTick& tick, server::ClientId client) {
  std::vector<std::string> out;
  for (const server::OutgoingGameMessage& m : tick.messages) {
    if (m.client == client) out.push_back(m.payload);
  }
  return out;
}

// A zap is a ray cast: it passes through its own player and shots, knocks the ball
// it meets, and stops at the first solid body in its way.
TEST(GoalRush, AZapKnocksTheBallUnlessSomethingIsInTheWay) {
  Game game;
  const auto zapper = game.run.join();  // the left player, facing right
  ASSERT_TRUE(zapper);
  game.run.step(30);                                // on the ground
  place_ball(game, {0.0, 0.6});                     // on the ground too, in line
  ASSERT_TRUE(game.run.message(*zapper, "shoot"));  // a shot inside the player first
  ASSERT_TRUE(game.run.message(*zapper, "zap"));
  const physics_testing::GameTick& knocked = game.run.step();
  EXPECT_EQ(told(knocked, *zapper), std::vector<std::string>{"zap ball"});
  EXPECT_GT(game.run.body("ball")->velocity.x, 7.0);  // 4 N s on 0.5 kg: 8 m/s

  // A crate between the player and the ball stops the zap there.
  place_ball(game, {0.0, 0.6});
  game.run.step();
  auto crate = std::make_shared<phys::BodyId>();
  game.rules->before_next_tick = [crate](server::GameWorld& world) {
    phys::BodyDef def;
    def.motion = phys::Motion::Static;
    def.position = {-4.0, 1.0};
    def.half_extents = {0.5, 1.0};
    *crate = world.create(def);
  };
  ASSERT_TRUE(game.run.message(*zapper, "zap"));
  const physics_testing::GameTick& blocked = game.run.step();
  EXPECT_EQ(told(blocked, *zapper), std::vector<std::string>{"zap blocked"});
  EXPECT_EQ(game.run.body("ball")->velocity.x, 0.0);

  // The crate gone and the ball up in the air, the zap meets the other player.
  const auto other = game.run.join();
  ASSERT_TRUE(other);
  game.run.step(30);
  game.rules->before_next_tick = [crate](server::GameWorld& world) {
    world.destroy(*crate);
    const phys::BodyId ball = *world.find_body("ball");
    world.set_position(ball, {0.0, 12.0});
  };
  ASSERT_TRUE(game.run.message(*zapper, "zap"));
  const physics_testing::GameTick& met = game.run.step();
  EXPECT_EQ(told(met, *zapper), std::vector<std::string>{"zap player"});
}

// The same joins, inputs and messages give the same world, tick for tick.
TEST(GoalRush, TheSamePlayGivesTheSameHashes) {
  const auto play = [] {
    Game game;
    const auto a = game.run.join();
    const auto b = game.run.join();
    for (int t = 0; t < 240; ++t) {
      EXPECT_TRUE(game.run.input(*a, t % 60 < 30 ? 20.0 : -20.0, 0.0));
      EXPECT_TRUE(game.run.input(*b, -15.0, 0.0));
      if (t % 40 == 0) {
        EXPECT_TRUE(game.run.message(*a, "jump"));
      }
      if (t % 50 == 10) {
        EXPECT_TRUE(game.run.message(*b, "shoot"));
      }
      game.run.step();
    }
    std::vector<std::uint64_t> hashes;
    for (const auto& tick : game.run.history()) hashes.push_back(tick.state_hash);
    return hashes;
  };
  const std::vector<std::uint64_t> first = play();
  EXPECT_EQ(first.size(), 240u);
  EXPECT_EQ(first, play());
}

// What the rules keep between ticks is in the world: a fresh rules object before
// every tick plays the same game (seats, facing, scores, shots and their expiry).
TEST(GoalRush, TheRulesKeepTheirStateInTheWorld) {
  const scene::SceneDef scene = goal_rush_scene();
  const auto script = [](GameRun& run, std::uint64_t tick) {
    if (tick == 1 || tick == 2 || tick == 230) {
      ASSERT_TRUE(run.join());
    }
    if (tick == 200) {
      ASSERT_TRUE(run.leave(1));
    }
    // The ball dropped over a goal now and then: goals and scores.
    if (tick == 20 || tick == 120 || tick == 260) {
      const phys::BodyId ball = *run.find_body("ball");
      ASSERT_TRUE(run.set_position(ball, tick == 120 ? 14.0 : -14.0, 5.0));
      ASSERT_TRUE(run.set_velocity(ball, 0.0, 0.0));
    }
    for (const auto& [client, body] : run.simulation().room().members()) {
      const double ax = (tick / 25 + client) % 2 == 0 ? 20.0 : -20.0;
      ASSERT_TRUE(run.input(client, ax, 0.0));
      if ((tick + client * 7) % 30 == 0) {
        ASSERT_TRUE(run.message(client, "shoot"));
      }
      if ((tick + client * 11) % 45 == 0) {
        ASSERT_TRUE(run.message(client, "jump"));
      }
      if ((tick + client * 5) % 70 == 0) {
        ASSERT_TRUE(run.message(client, "zap"));
      }
    }
  };
  const auto rules = [&scene] { return std::make_shared<GoalRushRules>(scene.player); };
  const auto check = physics_testing::check_rules_state_in_world(scene, rules, script, 320);
  ASSERT_TRUE(check) << check.message();
  // It played: goals were scored and shots were made and expired.
  EXPECT_GE(check->messages, 3u);
}

// Over the network: a shot asked for by a client reaches every client as a new body,
// and a third player hears why it was refused.
TEST(GoalRush, OverTheNetworkShotsAppearAndAThirdPlayerIsRefused) {
  const scene::SceneDef scene = goal_rush_scene();
  server::ServerConfig config = physics_testing::test_server_config();
  config.rules = std::make_shared<GoalRushRules>(scene.player);
  physics_testing::InProcessServer server(scene, config);
  auto players = physics_testing::connect_clients(server.client_config("player"), 2);
  ASSERT_TRUE(players);
  client::Client& shooter = *(*players)[0];
  client::Client& watcher = *(*players)[1];
  ASSERT_TRUE(shooter.send_game_message(shooter.welcome().current_tick + 2, "shoot"));
  const auto shot_seen = [](const client::Snapshot& snapshot) {
    return std::any_of(snapshot.added.begin(), snapshot.added.end(),
                       [](const client::BodyShape& shape) { return shape.name == "shot"; });
  };
  EXPECT_TRUE(physics_testing::wait_for_snapshot(watcher, shot_seen, 3s, "the shot"));

  client::Client third(server.client_config("third"));
  EXPECT_FALSE(third.connect(3s));
  ASSERT_TRUE(third.last_error().server);
  EXPECT_EQ(third.last_error().server->code, client::ErrorCode::RefusedByGame);
  EXPECT_NE(third.last_error().server->message.find("the game is full"), std::string::npos);
}

}  // namespace
