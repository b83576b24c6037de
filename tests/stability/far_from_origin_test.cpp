// Far from the origin. The core uses doubles (Vec2, vec2.h): 100 km
// from the origin a double resolves 1.5e-11 m, a float only 7.8 mm, which is more
// than the slop. Bound: each scene built 100,000 m away (on both axes) follows
// the scene built at the origin to within 1e-6 m in position and 1e-6 m/s in
// velocity, for every dynamic body on every step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "stability_scenes.h"

namespace phys::testing {
namespace {

constexpr Vec2 kFar{100'000.0, 100'000.0};
constexpr double kTolerance = 1.0e-6;

struct FarCase {
  const char* name;
  std::function<WorldSettings()> settings;
  std::function<void(World&, Vec2)> build;
  int steps;
};

const FarCase kCases[] = {
    {"bounce_half", [] { return WorldSettings{}; },
     [](World& w, Vec2 at) { add_dropped_ball(w, at, 10.0, 0.5); }, 600},
    {"bounce_elastic", [] { return WorldSettings{}; },
     [](World& w, Vec2 at) { add_dropped_ball(w, at, 10.0, 1.0); }, 600},
    {"column_of_ten", [] { return WorldSettings{}; },
     [](World& w, Vec2 at) { add_column(w, at, std::vector<double>(10, 1.0)); }, 1000},
    {"small_pyramid", [] { return WorldSettings{}; },
     [](World& w, Vec2 at) { add_pyramid(w, at, 10); }, 1000},
    {"slide_over_seams", [] { return WorldSettings{}; },
     [](World& w, Vec2 at) {
       add_tiled_floor(w, at, 40);
       BodyDef def = box_def(at + Vec2{0.0, 0.5}, {0.5, 0.5});
       def.velocity = {8.0, 0.0};
       def.friction = {0.5, 0.0};
       add_or_fail(w, def);
     },
     240},
    {"bullet", [] { return zero_gravity(); },
     [](World& w, Vec2 at) {
       add_bullet_and_wall(w, at, Shape::Circle, {200.0, 0.0});
     },
     60},
    {"two_masses", [] { return zero_gravity(); },
     [](World& w, Vec2 at) {
       BodyDef a = circle_def(at, 0.5);
       a.velocity = {4.0, 0.5};
       a.restitution = 1.0;
       BodyDef b = circle_def(at + Vec2{3.0, 0.0}, 0.5);
       b.mass = 3.0;
       b.restitution = 1.0;
       add_or_fail(w, a);
       add_or_fail(w, b);
     },
     120},
};

class FarFromOrigin : public ::testing::TestWithParam<FarCase> {};

TEST_P(FarFromOrigin, FollowsTheSceneAtTheOrigin) {
  World near(GetParam().settings());
  World far(GetParam().settings());
  GetParam().build(near, {0.0, 0.0});
  GetParam().build(far, kFar);
  double worst_position = 0.0;
  double worst_velocity = 0.0;
  for (int step = 1; step <= GetParam().steps; ++step) {
    near.step(kDt);
    far.step(kDt);
    const std::vector<BodyState> a = near.bodies();
    const std::vector<BodyState> b = far.bodies();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].motion == Motion::Static) continue;
      const Vec2 dp = (b[i].position - kFar) - a[i].position;
      const Vec2 dv = b[i].velocity - a[i].velocity;
      worst_position = std::max({worst_position, std::abs(dp.x), std::abs(dp.y)});
      worst_velocity = std::max({worst_velocity, std::abs(dv.x), std::abs(dv.y)});
      ASSERT_LE(length(dp), kTolerance) << "body " << i << " at step " << step;
      ASSERT_LE(length(dv), kTolerance) << "body " << i << " at step " << step;
    }
  }
  std::printf("far from origin, %s: worst position difference %.3g m, velocity %.3g m/s\n",
              GetParam().name, worst_position, worst_velocity);
  RecordProperty("worst_position_difference", std::to_string(worst_position));
}

INSTANTIATE_TEST_SUITE_P(Scenes, FarFromOrigin, ::testing::ValuesIn(kCases),
                         [](const auto& case_info) { return std::string(case_info.param.name); });

TEST(FarFromOrigin, FreeFlightFollowsTheClosedFormToAnUlpAStep) {
  // A ball thrown 100 km out follows x0 + v t + g t^2 / 2 (the Exact integrator is
  // exact for free flight). Each step rounds a coordinate near 1e5 at most twice
  // (the end of the step's path, then the move), by half an ulp each, and an ulp
  // there is 1.46e-11 m: after N steps the ball is within N ulps of the closed
  // form, about 1.7e-9 m after 2 s (a float world: up to 0.47 m).
  World world;
  const Vec2 v0{3.0, 12.0};
  BodyDef def = circle_def(kFar, 0.5);
  def.velocity = v0;
  const BodyId ball = add_or_fail(world, def);
  const Vec2 g = world.settings().gravity;
  const double ulp = std::nextafter(kFar.x + 100.0, 1e300) - (kFar.x + 100.0);
  for (int step = 1; step <= 120; ++step) {
    world.step(kDt);
    const double t = step / 60.0;
    const Vec2 expected = kFar + v0 * t + g * (0.5 * t * t);
    const Vec2 p = world.body(ball)->position;
    ASSERT_NEAR(p.x, expected.x, step * ulp) << "at step " << step;
    ASSERT_NEAR(p.y, expected.y, step * ulp) << "at step " << step;
  }
  const Vec2 p = world.body(ball)->position;
  const Vec2 expected = kFar + v0 * 2.0 + g * 2.0;
  std::printf("far from origin, free flight: off the closed form by %.3g m, %.3g m (bound %.3g)\n",
              p.x - expected.x, p.y - expected.y, 120 * ulp);
}

}  // namespace
}  // namespace phys::testing
