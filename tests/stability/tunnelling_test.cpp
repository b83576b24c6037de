// Tunnelling. Bound: a circle of radius 0.1 (and a box of side 0.1)
// at 200 m/s toward a static wall 0.1 m thick, at 60 Hz (3.3 m a step, 11 times
// the wall and bullet together), never gets further than the slop into the wall,
// on any step. With continuous = false the same bullet does pass through: it is
// the swept test that stops it.
#include <gtest/gtest.h>

#include "stability_scenes.h"

namespace phys::testing {
namespace {

constexpr double kEps = 1.0e-12;

struct Case {
  const char* name;
  Shape shape;
  Vec2 velocity;
  double restitution;
};

class Tunnelling : public ::testing::TestWithParam<Case> {};

TEST_P(Tunnelling, FastBulletNeverPassesTheWall) {
  World world(zero_gravity());
  const BulletScene scene = add_bullet_and_wall(world, {0.0, 0.0}, GetParam().shape,
                                                GetParam().velocity, GetParam().restitution);
  const double slop = world.settings().slop;
  const auto bullet = [&] { return *world.body(scene.bullet); };
  for (int step = 0; step < 120; ++step) {
    world.step(kDt);
    const BodyState b = bullet();
    ASSERT_TRUE(is_finite(b.position));
    ASSERT_LE(b.position.x + scene.bullet_half, scene.wall_left + slop + kEps)
        << "inside or past the wall at step " << step;
  }
  EXPECT_GT(world.counters().swept_hits, 0u);
  EXPECT_LE(bullet().velocity.x, 0.0) << "still moving into the wall";
}

TEST_P(Tunnelling, WithoutContinuousCollisionTheBulletPassesThrough) {
  WorldSettings settings = zero_gravity();
  settings.continuous = false;
  World world(settings);
  const BulletScene scene =
      add_bullet_and_wall(world, {0.0, 0.0}, GetParam().shape, GetParam().velocity);
  world.step(kDt);
  world.step(kDt);
  world.step(kDt);
  // After 3 steps (10 m) the bullet is on the far side: the mechanism matters.
  EXPECT_GT(world.body(scene.bullet)->position.x - scene.bullet_half, scene.wall_left + 0.1);
}

INSTANTIATE_TEST_SUITE_P(
    Bullets, Tunnelling,
    ::testing::Values(Case{"circle_head_on", Shape::Circle, {200.0, 0.0}, 0.0},
                      Case{"box_head_on", Shape::Box, {200.0, 0.0}, 0.0},
                      Case{"circle_diagonal", Shape::Circle, {200.0, 100.0}, 0.0},
                      Case{"box_diagonal", Shape::Box, {200.0, -100.0}, 0.0},
                      Case{"circle_elastic", Shape::Circle, {200.0, 0.0}, 1.0}),
    [](const auto& case_info) { return std::string(case_info.param.name); });

}  // namespace
}  // namespace phys::testing
