// The velocity solver's two frictionless paths, each run by the world itself: the
// iterations two contacts at a time in SIMD lanes (WorldSettings::simd_contact_lanes,
// the default where the build has SSE2) and one contact at a time (the setting off,
// and every build without SSE2). The lanes promise the one-at-a-time pass's results
// bit for bit (server/core/src/contact_lanes.h), so the same scene stepped both ways
// must leave every body with the same bits and the same state hash.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "contact_lanes.h"
#include "physics/world.h"
#include "scenes/scene_spec.h"
#include "scenes/scenes.h"

namespace phys::testing {
namespace {

struct Run {
  std::vector<BodyState> bodies;
  std::uint64_t hash = 0;
  StageCounters counters;
};

Run run(const scenes::SceneSpec& scene, bool lanes, int steps, double dt) {
  WorldSettings settings;
  settings.gravity = scene.gravity;
  settings.simd_contact_lanes = lanes;
  World world(settings);
  scenes::add_to_world(world, scene);
  for (int i = 0; i < steps; ++i) world.step(dt);
  Run result;
  world.for_each_body([&](const BodyState& b) { result.bodies.push_back(b); });
  result.hash = world.state_hash();
  result.counters = world.counters();
  return result;
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_same_bits(const Run& lanes, const Run& scalar) {
  ASSERT_EQ(lanes.bodies.size(), scalar.bodies.size());
  for (std::size_t i = 0; i < lanes.bodies.size(); ++i) {
    const BodyState& a = lanes.bodies[i];
    const BodyState& b = scalar.bodies[i];
    ASSERT_EQ(bits(a.position.x), bits(b.position.x)) << "body " << i;
    ASSERT_EQ(bits(a.position.y), bits(b.position.y)) << "body " << i;
    ASSERT_EQ(bits(a.velocity.x), bits(b.velocity.x)) << "body " << i;
    ASSERT_EQ(bits(a.velocity.y), bits(b.velocity.y)) << "body " << i;
    ASSERT_EQ(a.awake, b.awake) << "body " << i;
  }
  EXPECT_EQ(lanes.hash, scalar.hash);
  EXPECT_EQ(lanes.counters, scalar.counters);
}

// Each scene must have had contacts for the solver (or the comparison says nothing).
void compare(const scenes::SceneSpec& scene, int steps) {
  SCOPED_TRACE(scene.name);
  const Run lanes = run(scene, true, steps, scene.dt);
  const Run scalar = run(scene, false, steps, scene.dt);
  EXPECT_GT(scalar.counters.velocity_solves, 0u);
  expect_same_bits(lanes, scalar);
}

TEST(SolverPaths, TheBuildHasBothPaths) {
#if defined(__SSE2__)
  EXPECT_TRUE(kHaveContactLanes);
#else
  EXPECT_FALSE(kHaveContactLanes) << "without SSE2 only the one-at-a-time pass exists";
#endif
}

TEST(SolverPaths, FrictionlessRainedPileIsTheSameBitForBit) {
  scenes::RainedCircles rain;
  rain.circles = 400;
  rain.mu = 0.0;  // frictionless: the lanes' case
  compare(scenes::rained_circles_scene(rain), 400);
}

TEST(SolverPaths, FallingLatticeIsTheSameBitForBit) {
  compare(scenes::rain_scene(600, 300, 10, 10), 300);
}

TEST(SolverPaths, BoxPyramidIsTheSameBitForBit) { compare(scenes::pyramid_scene(20, 240), 240); }

// With contact friction the solver has one path (the scalar pass with friction);
// the setting must change nothing there.
TEST(SolverPaths, TheSettingChangesNothingWithFriction) {
  scenes::RainedCircles rain;
  rain.circles = 200;
  rain.mu = 0.5;
  compare(scenes::rained_circles_scene(rain), 300);
}

}  // namespace
}  // namespace phys::testing
