// Restitution: a ball of radius 0.5 dropped with its bottom 10 m over
// the floor at 60 Hz. Apexes are the highest points of the simulated trajectory
// (ApexTracker: the top of the parabola inside the step where v_y turns).
// Bounds:
//   e = 1:   each of the first 36 bounce apexes within 0.1% of 10 m.
//   e = 0.5: apex n within 2% of e^(2n) * 10 m for n = 1..5.
//   e = 0.5: the ball comes fully to rest (velocity exactly zero) within 10 s
//            (the infinite series of ideal bounces ends at 4.28 s) and stays so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "stability_scenes.h"

namespace phys::testing {
namespace {

constexpr double kDrop = 10.0;

// Steps the dropped ball and returns the first `count` bounce apexes (bottom of the
// ball over the floor), or fewer if it stopped bouncing within `max_steps`.
std::vector<double> bounce_apexes(double restitution, int count, int max_steps) {
  World world;
  const BodyId ball = add_dropped_ball(world, {0.0, 0.0}, kDrop, restitution);
  ApexTracker tracker(-world.settings().gravity.y);
  std::vector<double> apexes;
  for (int step = 0; step < max_steps && static_cast<int>(apexes.size()) < count; ++step) {
    world.step(kDt);
    const BodyState s = *world.body(ball);
    if (tracker.add(s.position.y - 0.5, s.velocity.y)) apexes.push_back(tracker.last_apex());
  }
  return apexes;
}

TEST(Restitution, ElasticBallKeepsItsApexWithinATenthOfAPercentFor36Bounces) {
  // 36 bounces of 2.86 s each take 103 s: 6200 steps; 8000 allowed.
  const std::vector<double> apexes = bounce_apexes(1.0, 36, 8000);
  ASSERT_EQ(apexes.size(), 36u) << "stopped bouncing";
  double worst = 0.0;
  for (std::size_t n = 0; n < apexes.size(); ++n) {
    worst = std::max(worst, std::abs(apexes[n] - kDrop) / kDrop);
    EXPECT_NEAR(apexes[n], kDrop, 0.001 * kDrop) << "bounce " << n + 1;
  }
  RecordProperty("worst_relative_apex_error", std::to_string(worst));
  std::printf("e=1: apex after 36 bounces %.6f m, worst relative error %.3g\n", apexes.back(),
              worst);
}

TEST(Restitution, HalfElasticApexesFollowESquaredToTheNWithinTwoPercent) {
  const std::vector<double> apexes = bounce_apexes(0.5, 5, 1200);
  ASSERT_EQ(apexes.size(), 5u) << "stopped bouncing early";
  for (std::size_t i = 0; i < apexes.size(); ++i) {
    const double n = static_cast<double>(i + 1);
    const double expected = std::pow(0.5, 2.0 * n) * kDrop;
    std::printf("e=0.5: apex %zu: %.6f m, expected %.6f m (%.3f%%)\n", i + 1, apexes[i], expected,
                100.0 * (apexes[i] - expected) / expected);
    EXPECT_NEAR(apexes[i], expected, 0.02 * expected) << "bounce " << n;
  }
}

TEST(Restitution, HalfElasticBallComesFullyToRestInFiniteTime) {
  World world;
  const BodyId ball = add_dropped_ball(world, {0.0, 0.0}, kDrop, 0.5);
  int rest_step = -1;
  for (int step = 1; step <= 600; ++step) {  // 10 s
    world.step(kDt);
    const BodyState s = *world.body(ball);
    if (s.velocity == Vec2{0.0, 0.0}) {
      rest_step = step;
      break;
    }
  }
  ASSERT_GT(rest_step, 0) << "still moving after 10 s";
  std::printf("e=0.5: at rest after %.3f s\n", rest_step * kDt);
  const double rest_height = world.body(ball)->position.y;
  for (int step = 0; step < 300; ++step) {  // and it stays at rest: no micro-bounces
    world.step(kDt);
    const BodyState s = *world.body(ball);
    ASSERT_EQ(s.velocity, (Vec2{0.0, 0.0})) << "moved again " << step << " steps later";
    ASSERT_EQ(s.position.y, rest_height);
  }
  EXPECT_NEAR(rest_height - 0.5, 0.0, world.settings().slop + 1.0e-12);
}

}  // namespace
}  // namespace phys::testing
