// physics_testing::GameRun: the rules called as the server calls them, the world and
// the events of each tick, and refusals that say why.
#include "physics_testing/game_run.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "physics_testing/in_process_server.h"
#include "scene/scene.h"
#include "server/simulation.h"

namespace {

using physics_testing::GameRun;

// Writes down every call, refuses a third player, answers "ping" with "pong", and
// makes a named crate at tick 3.
class Recorder : public server::GameRules {
 public:
  std::vector<std::string> calls;
  void on_create(server::GameWorld&) override { calls.push_back("create"); }
  server::JoinDecision on_join(server::GameWorld& world, server::ClientId client,
                               std::optional<std::uint32_t>) override {
    calls.push_back("join " + std::to_string(client));
    server::JoinDecision decision;
    if (world.players().size() == 2) decision.refuse = "two is company";
    return decision;
  }
  void on_leave(server::GameWorld&, server::ClientId client) override {
    calls.push_back("leave " + std::to_string(client));
  }
  void before_step(server::GameWorld& world,
                   const std::vector<server::AppliedInput>& inputs) override {
    calls.push_back("before " + std::to_string(world.tick()) + " inputs " +
                    std::to_string(inputs.size()));
    for (const server::ClientGameMessage& message : world.messages()) {
      if (message.payload == "ping") world.send(message.client, "pong");
    }
    if (world.tick() == 3) {
      phys::BodyDef crate;
      crate.position = {0.0, 15.0};
      crate.name = "crate";
      world.create(crate);
    }
  }
  void after_step(server::GameWorld& world) override {
    calls.push_back("after " + std::to_string(world.tick()));
  }
  void on_end(server::GameWorld&) override { calls.push_back("end"); }
};

TEST(GameRun, CallsTheRulesAsTheServerDoesAndKeepsEachTick) {
  auto rules = std::make_shared<Recorder>();
  {
    GameRun run(scene::default_scene(), rules);
    const auto a = run.join();
    const auto b = run.join();
    ASSERT_TRUE(a);
    ASSERT_TRUE(b);
    EXPECT_EQ(*a, 1u);
    EXPECT_EQ(*b, 2u);
    const auto refused = run.join();
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.message().find("two is company"), std::string::npos) << refused.message();
    ASSERT_TRUE(run.input(*a, 5.0, 0.0));
    ASSERT_TRUE(run.message(*b, "ping"));
    EXPECT_EQ(run.step().tick, 1u);
    EXPECT_EQ(run.messages_to(*b), std::vector<std::string>{"pong"});
    EXPECT_TRUE(run.messages_to(*a).empty());
    EXPECT_FALSE(run.find_body("crate"));
    run.step(2);
    EXPECT_EQ(run.tick(), 3u);
    ASSERT_TRUE(run.body("crate"));
    EXPECT_LT(run.body("crate")->position.y, 15.0);  // made before tick 3's step, fell in it
    ASSERT_EQ(run.history().size(), 3u);
    EXPECT_EQ(run.history().back().state_hash, run.world().state_hash());
    ASSERT_TRUE(run.leave(*a));
    EXPECT_FALSE(run.leave(*a));
    EXPECT_FALSE(run.input(*a, 1.0, 0.0));
  }
  const std::vector<std::string> expected{"create",
                                          "join 1",
                                          "join 2",
                                          "join 3",
                                          "before 1 inputs 1",
                                          "after 1",
                                          "before 2 inputs 0",
                                          "after 2",
                                          "before 3 inputs 0",
                                          "after 3",
                                          "leave 1",
                                          "end"};
  EXPECT_EQ(rules->calls, expected);
}

// The same world as the server's own Simulation, tick for tick.
TEST(GameRun, StepsTheServersSimulation) {
  GameRun run(scene::default_scene(), std::make_shared<Recorder>());
  server::Simulation simulation(scene::default_scene(), {}, std::make_shared<Recorder>());
  const auto a = run.join();
  ASSERT_TRUE(a);
  ASSERT_TRUE(simulation.admit(*a).body);
  for (int t = 1; t <= 60; ++t) {
    ASSERT_TRUE(run.input(*a, t % 20 < 10 ? 8.0 : -8.0, 0.0));
    EXPECT_TRUE(
        simulation.submit_input(*a, static_cast<std::uint64_t>(t), {t % 20 < 10 ? 8.0 : -8.0, 0.0})
            .accepted());
    EXPECT_EQ(run.step().state_hash, (simulation.step_tick(), simulation.world().state_hash()));
  }
}

TEST(GameRun, RefusedMessagesSayWhy) {
  GameRun run(scene::default_scene(), std::make_shared<Recorder>());
  const auto a = run.join();
  ASSERT_TRUE(a);
  const auto too_large = run.message(*a, std::string(server::kMaxGameMessageBytes + 1, 'x'));
  ASSERT_FALSE(too_large);
  EXPECT_NE(too_large.message().find("bytes"), std::string::npos) << too_large.message();
  for (std::size_t i = 0; i < server::kMaxGameMessagesPerTick; ++i) {
    ASSERT_TRUE(run.message(*a, "m"));
  }
  const auto too_many = run.message(*a, "m");
  ASSERT_FALSE(too_many);
  EXPECT_NE(too_many.message().find("messages at that tick"), std::string::npos);
  EXPECT_FALSE(run.message(99, "m"));
}

}  // namespace
