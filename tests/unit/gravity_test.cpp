// A body in free fall for N steps against the closed form of each integrator:
//   Exact:             y_N = y0 + v0 t + g t^2 / 2                (t = N dt)
//   SemiImplicitEuler: y_N = y0 + v0 t + g dt^2 N (N + 1) / 2     (moves with new v)
//   ExplicitEuler:     y_N = y0 + v0 t + g dt^2 N (N - 1) / 2     (moves with old v)
// and in every case v_N = v0 + g t. The bound 1e-11 m is rounding over 120 steps.
#include <gtest/gtest.h>

#include <string>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

constexpr int kSteps = 120;
constexpr double kG = -9.81;
constexpr Vec2 kStart{-2.0, 100.0};
constexpr Vec2 kLaunch{3.0, 4.0};
constexpr double kRounding = 1.0e-11;

class FreeFall : public WorldTest, public ::testing::WithParamInterface<Integrator> {
 protected:
  void SetUp() override {
    WorldSettings settings;
    settings.gravity = {0.0, kG};
    settings.integrator = GetParam();
    reset(settings);
    BodyDef def = circle_def(kStart, 0.5);
    def.velocity = kLaunch;
    ball_ = add(def);
  }
  BodyId ball_;
};

TEST_P(FreeFall, MatchesTheClosedFormOfItsIntegrator) {
  const double n = kSteps;
  const double t = n * kDt;
  double gravity_term = 0.0;
  switch (GetParam()) {
    case Integrator::Exact:
      gravity_term = kG * t * t / 2.0;
      break;
    case Integrator::SemiImplicitEuler:
      gravity_term = kG * kDt * kDt * n * (n + 1.0) / 2.0;
      break;
    case Integrator::ExplicitEuler:
      gravity_term = kG * kDt * kDt * n * (n - 1.0) / 2.0;
      break;
  }
  step_n(kSteps);
  const BodyState ball = state(ball_);
  EXPECT_NEAR(ball.position.x, kStart.x + kLaunch.x * t, kRounding);
  EXPECT_NEAR(ball.position.y, kStart.y + kLaunch.y * t + gravity_term, kRounding);
  EXPECT_NEAR(ball.velocity.x, kLaunch.x, kRounding);
  EXPECT_NEAR(ball.velocity.y, kLaunch.y + kG * t, kRounding);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, FreeFall,
                         ::testing::Values(Integrator::ExplicitEuler, Integrator::SemiImplicitEuler,
                                           Integrator::Exact),
                         [](const auto& case_info) {
                           return test_name(to_string(case_info.param));
                         });

class Gravity : public WorldTest {};

TEST_F(Gravity, ExactIntegratorIsOnTheParabolaAtEveryStep) {
  BodyDef def = circle_def(kStart, 0.5);
  def.velocity = kLaunch;
  const BodyId ball = add(def);
  for (int step = 1; step <= kSteps; ++step) {
    world_.step(kDt);
    const double t = step * kDt;
    ASSERT_NEAR(position(ball).y, kStart.y + kLaunch.y * t + kG * t * t / 2.0, kRounding)
        << "step " << step;
  }
}

TEST_F(Gravity, SidewaysGravityPullsSideways) {
  WorldSettings settings;
  settings.gravity = {2.0, 0.0};
  reset(settings);
  const BodyId ball = make_circle({0.0, 0.0});
  step_n(60);
  EXPECT_NEAR(position(ball).x, 2.0 * 1.0 / 2.0, kRounding);  // g t^2 / 2, t = 1
  EXPECT_EQ(position(ball).y, 0.0);
}

TEST_F(Gravity, AccelerationAddsToGravity) {
  // a + g = (1, 9.81 - 9.81) = (1, 0): the body hovers and accelerates sideways.
  const BodyId ball = make_circle({0.0, 0.0});
  ASSERT_TRUE(world_.set_acceleration(ball, {1.0, 9.81}));
  step_n(60);
  EXPECT_NEAR(position(ball).x, 0.5, kRounding);
  EXPECT_NEAR(position(ball).y, 0.0, kRounding);
  EXPECT_NEAR(velocity(ball).x, 1.0, kRounding);
}

}  // namespace
}  // namespace phys::testing
