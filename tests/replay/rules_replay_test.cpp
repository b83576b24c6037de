// A run with game rules, recorded, is replayed by running the same rules again
// (server::Replayer with the rules): every tick's hash equal. Replayed without the
// rules it differs, first at the tick they first changed the world.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "replay_support.h"
#include "replayer.h"
#include "server/simulation.h"
#include "server/tick_recorder.h"

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
  EXPECT_EQ(differs.first_difference.tick, 10u);  // the first ball
}

// Game messages recorded as delivered, replayed at their ticks: a "jump" kicks the
// sender's body, so a replay that missed one, or put it at another tick, differs.
class JumpRules : public server::GameRules {
 public:
  void before_step(server::GameWorld& w, const std::vector<server::AppliedInput>&) override {
    for (const server::ClientGameMessage& m : w.messages()) {
      if (m.payload == "jump") w.apply_impulse(*w.body_of(m.client), {0.0, 4.0});
    }
  }
};

TEST(RulesReplay, GameMessagesAreRecordedAndReplayedAtTheirTicks) {
  TempFile file("messages.precord");
  {
    server::Simulation sim(scene::default_scene(), {}, std::make_shared<JumpRules>());
    std::string error;
    auto recorder = server::TickRecorder::create(file.path(), sim.scene(), sim.tick_rate(),
                                                 sim.max_ticks_ahead(), {}, &error);
    ASSERT_TRUE(recorder) << error;
    sim.record_to(std::move(recorder));
    ASSERT_TRUE(sim.join(1).has_value());
    for (std::uint64_t t = 1; t <= 90; ++t) {
      if (t % 30 == 3) sim.submit_game_message(1, t, "jump");
      sim.submit_input(1, t, scripted_input(0, t));
      sim.step_tick();
    }
    sim.record_to(nullptr);
  }
  EXPECT_EQ(count_kind(load_or_fail(file.path()), physics::recording::Record::kGameMessage), 3u);
  auto replayer = replay::Replayer::open(file.path(), std::make_shared<JumpRules>());
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<replay::Replayer>>(replayer));
  const replay::ReplayReport report =
      replay::check_recording(*std::get<std::unique_ptr<replay::Replayer>>(replayer));
  EXPECT_EQ(report.outcome, replay::ReplayReport::Outcome::Equal);
  EXPECT_EQ(report.hashes_checked, 90u);
}

}  // namespace
}  // namespace rtest
