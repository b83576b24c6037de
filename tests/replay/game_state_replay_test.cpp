// A recorded game whose rules keep their state in the world's game state, timers
// included, replays tick for tick with the same rules: the recording holds no game
// state, the rules make it again from the same joins, inputs and messages, and every
// tick's hash (which covers the game state) is checked.
#include <gtest/gtest.h>

#include <memory>
#include <variant>

#include "replay_support.h"
#include "replayer.h"
#include "server/game_rules.h"

namespace rtest {
namespace {

// Every 12 ticks a kick for every player, counted; every second kick a ball.
class KickTimerRules : public server::GameRules {
 public:
  void on_create(server::GameWorld& w) override { w.start_timer("kick", 12, 12); }
  void on_timer(server::GameWorld& w, std::string_view, std::uint64_t) override {
    const std::int64_t kicks = w.get_int("kicks") + 1;
    w.set_int("kicks", kicks);
    for (const auto& [client, body] : w.players()) w.apply_impulse(body, {0.5, 2.0});
    if (kicks % 2 == 0) {
      phys::BodyDef ball;
      ball.shape = phys::Shape::Circle;
      ball.radius = 0.3;
      ball.position = {static_cast<double>(kicks % 5) - 2.0, 6.0};
      w.create(ball);
    }
  }
};

replay::ReplayReport replay_with(const TempFile& file, std::shared_ptr<server::GameRules> rules) {
  auto opened = replay::Replayer::open(file.path(), std::move(rules));
  EXPECT_TRUE(std::holds_alternative<std::unique_ptr<replay::Replayer>>(opened));
  return replay::check_recording(*std::get<std::unique_ptr<replay::Replayer>>(opened));
}

TEST(GameStateReplay, TimersAndVariablesReplayEveryTick) {
  TempFile file("timers.precord");
  const std::vector<std::uint64_t> live =
      record_in_process(file.path(), 2, 120, {}, std::make_shared<KickTimerRules>());
  ASSERT_EQ(live.size(), 120u);

  const replay::ReplayReport same = replay_with(file, std::make_shared<KickTimerRules>());
  EXPECT_EQ(same.outcome, replay::ReplayReport::Outcome::Equal);
  EXPECT_EQ(same.ticks, 120u);
  EXPECT_EQ(same.hashes_checked, 120u);

  // Without the rules there is no timer in the world: the hash differs at once.
  const replay::ReplayReport without = replay_with(file, nullptr);
  EXPECT_EQ(without.outcome, replay::ReplayReport::Outcome::Diverged);
  EXPECT_EQ(without.first_difference.tick, 1u);
}

}  // namespace
}  // namespace rtest
