// A run with game rules, recorded, is replayed by running the same rules again
// (server::Replayer with the rules): every tick's hash equal. Replayed without the
// rules it differs, first at the tick they first changed the world.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "replay_support.h"
#include "replayer.h"

namespace rtest {
namespace {

// From tick 10 on, a ball appears every 10 ticks; each 7th tick the first player's
// body is kicked; after each 25th the oldest ball is taken away.
class BallRules : public server::GameRules {
 public:
  std::vector<phys::BodyId> balls;
  void before_step(server::GameWorld& w, const std::vector<server::AppliedInput>& inputs) override {
    if (w.tick() % 10 == 0) {
      phys::BodyDef ball;
      ball.shape = phys::Shape::Circle;
      ball.radius = 0.3;
      ball.position = {static_cast<double>(balls.size() % 5) - 2.0, 6.0};
      balls.push_back(w.create(ball));
    }
    if (w.tick() % 7 == 0 && !inputs.empty()) w.apply_impulse(inputs.front().body, {1.0, 2.0});
  }
  void after_step(server::GameWorld& w) override {
    if (w.tick() % 25 == 0 && !balls.empty()) {
      w.destroy(balls.front());
      balls.erase(balls.begin());
    }
  }
};

TEST(RulesReplay, TheSameRulesReplayEveryTickAndNoRulesDifferWhereTheyActed) {
  TempFile file("rules.precord");
  const std::vector<std::uint64_t> live =
      record_in_process(file.path(), 2, 120, {}, std::make_shared<BallRules>());
  ASSERT_EQ(live.size(), 120u);

  auto with_rules = replay::Replayer::open(file.path(), std::make_shared<BallRules>());
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<replay::Replayer>>(with_rules));
  const replay::ReplayReport same =
      replay::check_recording(*std::get<std::unique_ptr<replay::Replayer>>(with_rules));
  EXPECT_EQ(same.outcome, replay::ReplayReport::Outcome::Equal);
  EXPECT_EQ(same.ticks, 120u);
  EXPECT_EQ(same.hashes_checked, 120u);

  auto without = replay::Replayer::open(file.path());
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<replay::Replayer>>(without));
  const replay::ReplayReport differs =
      replay::check_recording(*std::get<std::unique_ptr<replay::Replayer>>(without));
  EXPECT_EQ(differs.outcome, replay::ReplayReport::Outcome::Diverged);
  EXPECT_EQ(differs.first_difference.tick, 7u);  // the first kick
}

}  // namespace
}  // namespace rtest
