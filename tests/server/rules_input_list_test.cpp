// The inputs the game's rules are handed before each step (GameRules::before_step):
// a player's acceleration is listed at the ticks it differs from that player's last
// one, as a recording holds inputs, so that a replay hands the rules the same list.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "server/game_rules.h"
#include "server/simulation.h"
#include "test_scene.h"

namespace {

using server::AppliedInput;
using server::GameRules;
using server::GameWorld;

// Writes down each tick's list as "tick:client=(ax,ay)".
class InputListRules : public GameRules {
 public:
  std::vector<std::string> listed;
  void before_step(GameWorld& w, const std::vector<AppliedInput>& inputs) override {
    for (const AppliedInput& input : inputs) {
      listed.push_back(std::to_string(w.tick()) + ":" + std::to_string(input.client) + "=(" +
                       std::to_string(static_cast<int>(input.acceleration.x)) + "," +
                       std::to_string(static_cast<int>(input.acceleration.y)) + ")");
    }
  }
};

TEST(RulesInputList, AnInputIsListedWhenItDiffersFromThePlayersLastOne) {
  auto rules = std::make_shared<InputListRules>();
  server::Simulation sim(server_test::free_space_scene(), {}, rules);
  ASSERT_TRUE(sim.join(1).has_value());
  ASSERT_TRUE(sim.join(2).has_value());
  // Player 1: A, A, B, B, A, A. Player 2: C throughout. Listed: the first of each run.
  const std::vector<phys::Vec2> one{{1, 0}, {1, 0}, {0, 2}, {0, 2}, {1, 0}, {1, 0}};
  for (std::size_t i = 0; i < one.size(); ++i) {
    const std::uint64_t tick = sim.current_tick() + 1;
    sim.submit_input(1, tick, one[i]);
    sim.submit_input(2, tick, {3.0, 3.0});
    sim.step_tick();
  }
  EXPECT_EQ(rules->listed,
            (std::vector<std::string>{"1:1=(1,0)", "1:2=(3,3)", "3:1=(0,2)", "5:1=(1,0)"}));
}

}  // namespace
