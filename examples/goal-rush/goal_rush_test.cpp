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
  EXPECT_EQ(game.rules->side_of(*left), Side::Left);
  EXPECT_EQ(game.rules->side_of(*right), Side::Right);
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
  EXPECT_EQ(game.rules->score(Side::Right), 1);
  EXPECT_EQ(game.rules->score(Side::Left), 0);
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
  EXPECT_EQ(game.rules->score(Side::Left), 1);
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
  EXPECT_EQ(game.rules->score(Side::Left), 0);
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
  EXPECT_EQ(game.rules->shots_in_flight(), 1u);
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
  EXPECT_EQ(game.rules->shots_in_flight(), 0u);
  EXPECT_FALSE(game.run.find_body("shot"));
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(game.run.message(*shooter, "shoot"));
  game.run.step();
  EXPECT_EQ(game.rules->shots_in_flight(), goal_rush::kMaxShotsPerPlayer);
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
