// The world's queries through the rules' handle (GameWorld): rules that look along a
// line, into a box and at a point get the world's own answers, may create and destroy
// bodies while going through them, and have bad input refused, not thrown.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "server/game_rules.h"
#include "server/simulation.h"
#include "test_scene.h"

namespace {

using server::GameRules;
using server::GameWorld;
using server::Simulation;

// Tick 1: a row of crates at x = 2, 4, 6, 8 on y = 20. Tick 2: looks along the row,
// then turns every crate in a box around it into a ball above it. Tick 3: looks again.
class LookingRules : public GameRules {
 public:
  std::vector<phys::BodyId> crates;
  std::optional<phys::CastHit> first;
  std::vector<phys::CastHit> all;
  std::vector<phys::BodyId> in_box;
  std::vector<phys::BodyId> balls;
  std::vector<phys::BodyId> at_crate_after;
  std::vector<phys::BodyId> at_ball_after;
  phys::QueryError nan_error = phys::QueryError::None;
  bool nan_answered = true;

  void before_step(GameWorld& w, const std::vector<server::AppliedInput>&) override {
    if (w.tick() == 1) {
      for (int i = 1; i <= 4; ++i) {
        phys::BodyDef crate;
        crate.motion = phys::Motion::Static;
        crate.position = {2.0 * i, 20.0};
        crate.half_extents = {0.5, 0.5};
        crates.push_back(w.create(crate));
      }
    } else if (w.tick() == 2) {
      first = w.cast_ray({0.0, 20.0}, {10.0, 0.0});
      all = w.cast_ray_all({0.0, 20.0}, {10.0, 0.0});
      in_box = w.overlap_box({{0.0, 19.0}, {10.0, 21.0}});
      for (const phys::BodyId crate : in_box) {  // changing the world while going through
        phys::BodyDef ball;
        ball.shape = phys::Shape::Circle;
        ball.motion = phys::Motion::Static;
        ball.radius = 0.25;
        ball.position = w.body(crate)->position + phys::Vec2{0.0, 3.0};
        balls.push_back(w.create(ball));
        w.destroy(crate);
      }
      nan_answered = w.cast_ray({std::nan(""), 0.0}, {1.0, 0.0}, {}, &nan_error).has_value();
    } else if (w.tick() == 3) {
      at_crate_after = w.overlap_point({2.0, 20.0});
      at_ball_after = w.overlap_circle({2.0, 23.0}, 0.1);
    }
  }
};

TEST(GameWorldQueries, RulesLookAndChangeTheWorldAsTheyGo) {
  auto rules = std::make_shared<LookingRules>();
  Simulation sim(server_test::free_space_scene(), {}, rules);
  for (int i = 0; i < 3; ++i) sim.step_tick();

  ASSERT_EQ(rules->crates.size(), 4u);
  ASSERT_TRUE(rules->first.has_value());
  EXPECT_EQ(rules->first->body, rules->crates[0]);
  EXPECT_EQ(rules->first->fraction, 0.15);  // the first crate's face at x = 1.5
  EXPECT_EQ(rules->first->normal, (phys::Vec2{-1.0, 0.0}));
  ASSERT_EQ(rules->all.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(rules->all[i].body, rules->crates[i]);
  EXPECT_EQ(rules->in_box, rules->crates);
  EXPECT_FALSE(rules->nan_answered);
  EXPECT_EQ(rules->nan_error, phys::QueryError::NonFinite);
  // The crates became balls: the next tick's queries see the new world.
  EXPECT_TRUE(rules->at_crate_after.empty());
  ASSERT_EQ(rules->balls.size(), 4u);
  EXPECT_EQ(rules->at_ball_after, std::vector<phys::BodyId>{rules->balls[0]});
  for (const phys::BodyId crate : rules->crates) EXPECT_FALSE(sim.world().contains(crate));
}

}  // namespace
