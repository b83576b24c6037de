// Friction: the exact decay v*exp(-k dt) that replaces the lecture's
// lerp(v, 0, dt*k). For every dt*k >= 0 it never changes the sign of v and never
// makes |v| grow; the lerp does both once dt*k > 1, which the last tests document.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/formulas.h"

namespace phys {
namespace {

constexpr double kDt = 1.0 / 60.0;

class FrictionAtDtTimesK : public ::testing::TestWithParam<double> {
 protected:
  double rate() const { return GetParam() / kDt; }  // k such that dt*k = GetParam()
};

// rate()*kDt rounds back to dt*k within an ulp or two; exp turns that into a
// relative difference of about dt*k ulps, hence the relative bound 1e-13.
constexpr double kRounding = 1.0e-13;

TEST_P(FrictionAtDtTimesK, DecayFactorIsExpOfMinusKDt) {
  const double expected = std::exp(-GetParam());
  EXPECT_NEAR(friction_decay_factor(rate(), kDt), expected, kRounding * expected);
}

TEST_P(FrictionAtDtTimesK, EqualsExactDecayWithinRounding) {
  for (const double v : {10.0, -10.0, 1.0e-3, -123.456}) {
    const double expected = v * std::exp(-GetParam());
    EXPECT_NEAR(apply_friction(v, rate(), kDt), expected, kRounding * std::abs(expected))
        << "v=" << v;
  }
}

TEST_P(FrictionAtDtTimesK, NeverChangesSignNorGrows) {
  for (const double v0 : {10.0, -10.0, 1.0e-300, -1.0e300}) {
    double v = v0;
    for (int step = 0; step < 1000; ++step) {
      const double next = apply_friction(v, rate(), kDt);
      ASSERT_FALSE(next * v0 < 0.0) << "sign changed at step " << step << " v0=" << v0;
      ASSERT_LE(std::abs(next), std::abs(v)) << "grew at step " << step << " v0=" << v0;
      v = next;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(HandPicked, FrictionAtDtTimesK, ::testing::Values(0.5, 1.0, 2.0, 50.0));

TEST(Friction, HandComputedValues) {
  // dt*k = 0.5: 10 * e^-0.5 = 6.0653065971263...
  EXPECT_NEAR(apply_friction(10.0, 30.0, kDt), 6.0653065971263342, 1e-13);
  // dt*k = 1: 10/e = 3.6787944117144233
  EXPECT_NEAR(apply_friction(10.0, 60.0, kDt), 3.6787944117144233, 1e-13);
  // dt*k = 2: 10/e^2 = 1.3533528323661270
  EXPECT_NEAR(apply_friction(10.0, 120.0, kDt), 1.3533528323661270, 1e-13);
  // dt*k = 50: 10 e^-50 = 1.9287498479639177e-21
  EXPECT_NEAR(apply_friction(10.0, 3000.0, kDt), 1.9287498479639177e-21, 1e-34);
}

TEST(Friction, ZeroRateLeavesVelocityUntouched) {
  EXPECT_EQ(friction_decay_factor(0.0, kDt), 1.0);
  EXPECT_EQ(apply_friction(3.25, 0.0, kDt), 3.25);
  EXPECT_EQ(apply_friction(-3.25, 0.0, kDt), -3.25);
}

TEST(Friction, ZeroVelocityStaysZero) { EXPECT_EQ(apply_friction(0.0, 60.0, kDt), 0.0); }

TEST(Friction, HugeRateStopsWithoutOvershoot) {
  // dt*k = 1e6: exp underflows to exactly zero, never to a negative value or NaN.
  const double v = apply_friction(5.0, 6.0e7, kDt);
  EXPECT_TRUE(std::isfinite(v));
  EXPECT_GE(v, 0.0);
  EXPECT_LT(v, 1.0e-300);
}

// Documentation of why the lecture's formula is not used: lerp(v, 0, t).
TEST(LectureLerpFriction, OvershootsPastZeroAtOneAndAHalf) {
  EXPECT_EQ(lerp(10.0, 0.0, 1.5), -5.0);  // the velocity reversed
}

TEST(LectureLerpFriction, DivergesPastTwo) {
  double v = 10.0;
  for (int step = 0; step < 20; ++step) v = lerp(v, 0.0, 2.5);  // factor (1-2.5) = -1.5
  EXPECT_GT(std::abs(v), 10.0 * 3000.0);                        // 1.5^20 = 3325.3
}

TEST(LectureLerpFriction, AgreesWithExactDecayToFirstOrderForSmallDtK) {
  // For dt*k = 1e-3 the two differ by about (dt*k)^2/2 of v.
  const double lerp_value = lerp(10.0, 0.0, 1.0e-3);
  const double exact_value = apply_friction(10.0, 1.0e-3 / kDt, kDt);
  EXPECT_NEAR(lerp_value, exact_value, 10.0 * 1.0e-6);
  EXPECT_GT(std::abs(lerp_value - exact_value), 10.0 * 1.0e-7);
}

}  // namespace
}  // namespace phys
