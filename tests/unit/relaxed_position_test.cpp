// The relaxed position passes (WorldSettings::relaxed_position_passes): passes after
// the first find each circle pair's penetration from the bodies' moves along the
// normal the first pass found, instead of running the narrowphase again. Where that
// update is exact (bodies moving along one line), the result is the full
// narrowphase's to rounding; on rained piles the overlap left stays within the bound
// the accuracy report states for the rains (0.005 m).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "physics/world.h"
#include "physics_test_support.h"
#include "scenes/scene_spec.h"
#include "scenes/scenes.h"

namespace phys::testing {
namespace {

WorldSettings settings_with(bool relaxed, Vec2 gravity) {
  WorldSettings settings;
  settings.gravity = gravity;
  settings.relaxed_position_passes = relaxed;
  return settings;
}

std::vector<BodyState> states(const World& world) {
  std::vector<BodyState> out;
  world.for_each_body([&](const BodyState& b) { out.push_back(b); });
  return out;
}

// Four circles in a row on the X axis, overlapping and driven into each other
// head-on, no gravity: every normal is along X, every push moves bodies along it,
// so the linear update is the narrowphase's answer.
World head_on_row(bool relaxed) {
  World world(settings_with(relaxed, {0.0, 0.0}));
  const double xs[] = {0.0, 0.9, 1.75, 2.65};
  const double vs[] = {3.0, 1.0, -1.0, -3.0};
  for (int i = 0; i < 4; ++i) {
    BodyDef def;
    def.shape = Shape::Circle;
    def.radius = 0.5;
    def.mass = 1.0 + i;
    def.position = {xs[i], 0.0};
    def.velocity = {vs[i], 0.0};
    world.add_body(def);
  }
  return world;
}

TEST(RelaxedPositionPasses, HeadOnRowEqualsTheFullNarrowphase) {
  World relaxed = head_on_row(true);
  World full = head_on_row(false);
  for (int step = 0; step < 30; ++step) {
    relaxed.step(1.0 / 60.0);
    full.step(1.0 / 60.0);
    const auto a = states(relaxed);
    const auto b = states(full);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_NEAR(a[i].position.x, b[i].position.x, 1e-12) << "step " << step << " body " << i;
      EXPECT_EQ(a[i].position.y, 0.0);
      EXPECT_NEAR(a[i].velocity.x, b[i].velocity.x, 1e-9) << "step " << step << " body " << i;
    }
  }
  // The later passes ran, relaxed in one world and by the narrowphase in the other.
  EXPECT_GT(relaxed.counters().relaxed_pair_updates, 0u);
  EXPECT_EQ(full.counters().relaxed_pair_updates, 0u);
  EXPECT_LT(relaxed.counters().circle_circle_tests, full.counters().circle_circle_tests);
}

double largest_overlap(const World& world) { return max_overlap(states(world)); }

// A falling lattice and a tumbling rain, frictionless and rough: the overlap the
// passes leave at the end stays within the rains' bound, and the later passes ran
// relaxed.
void expect_overlap_bounded(const scenes::SceneSpec& scene, int steps) {
  SCOPED_TRACE(scene.name);
  World world(settings_with(true, scene.gravity));
  scenes::add_to_world(world, scene);
  for (int i = 0; i < steps; ++i) world.step(scene.dt);
  EXPECT_GT(world.counters().relaxed_pair_updates, 0u);
  EXPECT_LE(largest_overlap(world), 0.005);
}

TEST(RelaxedPositionPasses, FallingLatticeOverlapWithinTheBound) {
  expect_overlap_bounded(scenes::rain_scene(300, 240, 10, 10), 240);
}

TEST(RelaxedPositionPasses, RainedPilesOverlapWithinTheBound) {
  for (const double mu : {0.0, 0.5}) {
    scenes::RainedCircles rain;
    rain.circles = 300;
    rain.mu = mu;
    expect_overlap_bounded(scenes::rained_circles_scene(rain), 300);
  }
}

}  // namespace
}  // namespace phys::testing
