// lerp, and one step of each integrator (velocity and position updates), each
// against a value computed by hand. The numbers are chosen to be exact in binary
// (dt = 0.5, v = 2, a = 4), so the expectations are equalities.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "physics/formulas.h"
#include "physics/settings.h"

namespace phys {
namespace {

TEST(Lerp, EndpointsAndMidpoint) {
  EXPECT_EQ(lerp(2.0, 10.0, 0.0), 2.0);
  EXPECT_EQ(lerp(2.0, 10.0, 1.0), 10.0);
  EXPECT_EQ(lerp(2.0, 10.0, 0.5), 6.0);   // (1-0.5)*2 + 0.5*10
  EXPECT_EQ(lerp(2.0, 10.0, 0.25), 4.0);  // 0.75*2 + 0.25*10
  EXPECT_EQ(lerp(-4.0, 4.0, 0.75), 2.0);  // 0.25*-4 + 0.75*4
}

TEST(Lerp, ExtrapolatesOutsideZeroOne) {
  // lerp is a straight line, so t > 1 goes past v1: the root of the friction problem.
  EXPECT_EQ(lerp(2.0, 0.0, 1.5), -1.0);  // (1-1.5)*2
  EXPECT_EQ(lerp(2.0, 0.0, 3.0), -4.0);  // (1-3)*2
}

// x = 1, v = 2, a = 4, dt = 0.5, no friction.
constexpr double kX = 1.0;
constexpr double kV = 2.0;
constexpr double kA = 4.0;
constexpr double kStep = 0.5;

TEST(IntegrateAxis, ExplicitEulerMovesWithTheOldVelocity) {
  const AxisMotion m = integrate_axis(Integrator::ExplicitEuler, kX, kV, kA, 0.0, kStep);
  EXPECT_EQ(m.position, 2.0);  // 1 + 2*0.5
  EXPECT_EQ(m.velocity, 4.0);  // 2 + 4*0.5
}

TEST(IntegrateAxis, SemiImplicitEulerMovesWithTheNewVelocity) {
  const AxisMotion m = integrate_axis(Integrator::SemiImplicitEuler, kX, kV, kA, 0.0, kStep);
  EXPECT_EQ(m.velocity, 4.0);  // 2 + 4*0.5
  EXPECT_EQ(m.position, 3.0);  // 1 + 4*0.5
}

TEST(IntegrateAxis, ExactFollowsTheParabola) {
  const AxisMotion m = integrate_axis(Integrator::Exact, kX, kV, kA, 0.0, kStep);
  EXPECT_EQ(m.velocity, 4.0);  // 2 + 4*0.5
  EXPECT_EQ(m.position, 2.5);  // 1 + 2*0.5 + 4*0.25/2
}

TEST(IntegrateAxis, NothingMovesWithoutVelocityOrAcceleration) {
  for (const Integrator integrator :
       {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::Exact}) {
    const AxisMotion m = integrate_axis(integrator, 7.0, 0.0, 0.0, 3.0, kStep);
    EXPECT_EQ(m.position, 7.0) << to_string(integrator);
    EXPECT_EQ(m.velocity, 0.0) << to_string(integrator);
  }
}

TEST(IntegrateAxis, SemiImplicitEulerAppliesFrictionFirst) {
  // The recipe: v = v*exp(-k dt); v += a dt; x += v dt. k = 2, dt = 0.5: factor e^-1.
  // By hand (e^-1 = 0.36787944117144232160, to 20 digits): v1 = 2 e^-1 + 4*0.5 =
  // 2.7357588823428846432; x1 = 1 + 0.5 v1 = 2.3678794411714423216. Friction
  // after the acceleration would give 2 e^-1 + 2 e^-1 = 1.4715 instead.
  const double k = 2.0;
  const AxisMotion m = integrate_axis(Integrator::SemiImplicitEuler, kX, kV, kA, k, kStep);
  EXPECT_DOUBLE_EQ(m.velocity, 2.7357588823428847);
  EXPECT_DOUBLE_EQ(m.position, 2.3678794411714423);
  // The recipe restated, beside the hand values.
  const double v1 = kV * std::exp(-1.0) + kA * kStep;
  EXPECT_DOUBLE_EQ(m.velocity, v1);
  EXPECT_DOUBLE_EQ(m.position, kX + v1 * kStep);
}

TEST(IntegrateAxis, SemiImplicitEulerStepsSumToTheClosedForm) {
  // Without friction, n steps from x0, v0 give v_n = v0 + n a dt and
  // x_n = x0 + dt (v_1 + ... + v_n) = x0 + n v0 dt + a dt^2 n (n + 1) / 2.
  // x0 = 1, v0 = 2, a = 4, dt = 0.5, n = 4: v_4 = 2 + 8 = 10, x_4 = 1 + 4 + 10 = 15
  // (exact in binary). Explicit Euler's n (n - 1) / 2 would give x_4 = 11, and the
  // exact parabola's n^2 / 2 gives 13.
  double x = kX;
  double v = kV;
  for (int n = 0; n < 4; ++n) {
    const AxisMotion m = integrate_axis(Integrator::SemiImplicitEuler, x, v, kA, 0.0, kStep);
    x = m.position;
    v = m.velocity;
  }
  EXPECT_EQ(v, 10.0);
  EXPECT_EQ(x, 15.0);
}

TEST(IntegrateAxis, ExactSolvesDecayWithConstantAcceleration) {
  // dv/dt = a - k v: v(t) = a/k + (v0 - a/k) e^{-kt};
  // x(t) = x0 + (a/k) t + (v0 - a/k)(1 - e^{-kt})/k. k = 2, t = 0.5:
  // a/k = 2, v0 - a/k = 0, so v stays 2 and x = 1 + 2*0.5 = 2.
  const AxisMotion steady = integrate_axis(Integrator::Exact, kX, kV, kA, 2.0, kStep);
  EXPECT_DOUBLE_EQ(steady.velocity, 2.0);
  EXPECT_DOUBLE_EQ(steady.position, 2.0);
  // v0 = 6: v = 2 + 4/e = 3.4715..., x = 1 + 1 + 4(1 - 1/e)/2 = 3.2642...
  const AxisMotion decaying = integrate_axis(Integrator::Exact, kX, 6.0, kA, 2.0, kStep);
  EXPECT_DOUBLE_EQ(decaying.velocity, 2.0 + 4.0 * std::exp(-1.0));
  EXPECT_DOUBLE_EQ(decaying.position, 2.0 + 2.0 * (1.0 - std::exp(-1.0)));
  // By hand (e^-1 = 0.36787944117144232160): 3.4715177646857692864 and
  // 3.2642411176571153568.
  EXPECT_DOUBLE_EQ(decaying.velocity, 3.4715177646857693);
  EXPECT_DOUBLE_EQ(decaying.position, 3.2642411176571153);
}

TEST(IntegrateAxis, ExactWithFrictionOnlyTravelsTheDecayDistance) {
  // a = 0: x = x0 + v0 (1 - e^{-k dt}) / k. k = 4, dt = 0.5, v0 = 2: 1 + 0.5(1 - e^-2).
  const AxisMotion m = integrate_axis(Integrator::Exact, kX, kV, 0.0, 4.0, kStep);
  EXPECT_DOUBLE_EQ(m.velocity, 2.0 * std::exp(-2.0));
  EXPECT_DOUBLE_EQ(m.position, 1.0 + 0.5 * (1.0 - std::exp(-2.0)));
  // By hand (e^-2 = 0.13533528323661269189): 0.2706705664732253838 and
  // 1.43233235838169365405.
  EXPECT_DOUBLE_EQ(m.velocity, 0.2706705664732254);
  EXPECT_DOUBLE_EQ(m.position, 1.4323323583816936);
}

TEST(PositionAt, StartsAtXAndEndsWhereTheStepEnds) {
  for (const Integrator integrator :
       {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::Exact}) {
    for (const double k : {0.0, 2.0}) {
      const AxisMotion end = integrate_axis(integrator, kX, kV, kA, k, kStep);
      EXPECT_DOUBLE_EQ(position_at(integrator, kX, kV, kA, k, kStep, 0.0), kX)
          << to_string(integrator) << " k=" << k;
      EXPECT_DOUBLE_EQ(position_at(integrator, kX, kV, kA, k, kStep, kStep), end.position)
          << to_string(integrator) << " k=" << k;
    }
  }
}

TEST(PositionAt, ExactIsOnTheParabolaMidStep) {
  // x(0.25) = 1 + 2*0.25 + 4*0.0625/2 = 1.625.
  EXPECT_DOUBLE_EQ(position_at(Integrator::Exact, kX, kV, kA, 0.0, kStep, 0.25), 1.625);
}

TEST(IntegratorNames, AreDistinctAndNonEmpty) {
  const std::string explicit_euler = to_string(Integrator::ExplicitEuler);
  const std::string semi = to_string(Integrator::SemiImplicitEuler);
  const std::string exact = to_string(Integrator::Exact);
  EXPECT_FALSE(explicit_euler.empty());
  EXPECT_NE(explicit_euler, semi);
  EXPECT_NE(semi, exact);
  EXPECT_NE(explicit_euler, exact);
}

}  // namespace
}  // namespace phys
