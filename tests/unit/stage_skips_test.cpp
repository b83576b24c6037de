// "Model only what a scene needs": the StageCounters show each stage skipped when
// the scene cannot need it, and run when it can (so a counter stuck at zero
// cannot pass for a skip).
#include <gtest/gtest.h>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

class StageSkips : public WorldTest {
 protected:
  const StageCounters& counters() const { return world_.counters(); }
};

TEST_F(StageSkips, NoFrictionPassWhenEveryFrictionIsZero) {
  make_floor(0.0);
  make_box({0.0, 2.0});
  make_circle({3.0, 2.0});
  step_n(30);
  EXPECT_EQ(counters().friction_passes, 0u);
}

TEST_F(StageSkips, FrictionPassRunsWhenOneBodyHasFriction) {
  make_floor(0.0);
  make_box({0.0, 2.0});
  BodyDef def = circle_def({3.0, 2.0}, 0.5);
  def.friction = {0.0, 0.5};
  add(def);
  step_n(30);
  EXPECT_EQ(counters().friction_passes, 30u);
}

TEST_F(StageSkips, FrictionPassStopsWhenTheBodyWithFrictionIsRemoved) {
  BodyDef def = circle_def({3.0, 2.0}, 0.5);
  def.friction = {1.0, 0.0};
  const BodyId rough = add(def);
  make_box({0.0, 2.0});
  step_n(10);
  const std::uint64_t before = counters().friction_passes;
  EXPECT_GT(before, 0u);
  ASSERT_TRUE(world_.remove_body(rough));
  step_n(10);
  EXPECT_EQ(counters().friction_passes, before);
}

TEST_F(StageSkips, NoGravityTermWhenGravityIsZero) {
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  reset(settings);
  make_box({0.0, 0.0});
  step_n(30);
  EXPECT_EQ(counters().gravity_passes, 0u);
  EXPECT_EQ(counters().steps, 30u);
}

TEST_F(StageSkips, GravityTermRunsWhenGravityIsNotZero) {
  make_box({0.0, 0.0});
  step_n(30);
  EXPECT_EQ(counters().gravity_passes, 30u);
}

TEST_F(StageSkips, NoBoxTestsInACirclesOnlyScene) {
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  reset(settings);
  for (int i = 0; i < 10; ++i) make_circle({0.9 * i, 0.0}, 0.5);  // overlapping chain
  step_n(10);
  EXPECT_GT(counters().circle_circle_tests, 0u);
  EXPECT_EQ(counters().box_box_tests, 0u);
  EXPECT_EQ(counters().circle_box_tests, 0u);
}

TEST_F(StageSkips, BoxTestsRunWhenBoxesTouch) {
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  reset(settings);
  for (int i = 0; i < 10; ++i) make_box({0.9 * i, 0.0});
  make_circle({0.0, 0.9}, 0.5);
  step_n(10);
  EXPECT_GT(counters().box_box_tests, 0u);
  EXPECT_GT(counters().circle_box_tests, 0u);
}

TEST_F(StageSkips, StaticBodiesAreNeverIntegrated) {
  // 3 static + 2 dynamic bodies, 20 steps, no sleeping: 2 * 20 integrations.
  WorldSettings settings;
  settings.sleeping = false;
  reset(settings);
  make_floor(0.0);
  make_static_box({-10.0, 5.0}, {0.5, 5.0});
  make_static_circle({10.0, 5.0}, 1.0);
  make_box({0.0, 3.0});
  make_circle({4.0, 3.0});
  step_n(20);
  EXPECT_EQ(counters().bodies_integrated, 40u);
}

TEST_F(StageSkips, SubstepsIntegrateEachDynamicBodyOncePerSubstep) {
  WorldSettings settings;
  settings.sleeping = false;
  settings.substeps = 4;
  reset(settings);
  make_floor(0.0);
  make_box({0.0, 3.0});
  step_n(5);
  EXPECT_EQ(counters().substeps, 20u);
  EXPECT_EQ(counters().bodies_integrated, 20u);
}

TEST_F(StageSkips, SleepingBodiesAreSkipped) {
  make_floor(0.0);
  const BodyId box = make_box({0.0, 0.5});  // resting from the start
  step_n(120);                              // 2 s, well past sleep_time
  ASSERT_FALSE(state(box).awake) << "a resting box should fall asleep";
  EXPECT_EQ(world_.awake_body_count(), 0u);
  const std::uint64_t integrated = counters().bodies_integrated;
  const std::uint64_t skipped = counters().sleeping_bodies_skipped;
  const Vec2 asleep_at = position(box);
  step_n(60);
  EXPECT_EQ(counters().bodies_integrated, integrated);
  EXPECT_EQ(counters().sleeping_bodies_skipped, skipped + 60u);
  EXPECT_EQ(position(box), asleep_at);
}

TEST_F(StageSkips, ASleepingBodyHitByAnotherWakesUp) {
  make_floor(0.0);
  const BodyId sleeper = make_box({0.0, 0.5});
  step_n(120);
  ASSERT_FALSE(state(sleeper).awake);
  make_circle({0.0, 4.0}, 0.5);  // dropped onto it
  step_n(60);
  EXPECT_GT(counters().wakes, 0u);
}

TEST_F(StageSkips, SettingAnInputWakesASleepingBody) {
  make_floor(0.0);
  const BodyId box = make_box({0.0, 0.5});
  step_n(120);
  ASSERT_FALSE(state(box).awake);
  ASSERT_TRUE(world_.set_acceleration(box, {5.0, 0.0}));
  step_n(30);
  EXPECT_TRUE(state(box).awake);
  EXPECT_GT(position(box).x, 0.0);
}

}  // namespace
}  // namespace phys::testing
