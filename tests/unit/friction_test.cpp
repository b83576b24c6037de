// Friction: the exact decay v*exp(-k dt) that replaces the classic recipe's
// lerp(v, 0, dt*k). For every dt*k >= 0 it never changes the sign of v and never
// makes |v| grow; the lerp does both once dt*k > 1, which the last tests document.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/formulas.h"

namespace phys {
namespace {

constexpr double kDt = 1.0 / 60.0;

// dt*k, and e^-(dt*k) worked out by hand (to 40 digits with Python's decimal
// module, independently of the C library's exp, then rounded to the nearest double):
//   e^-0.5 = 0.6065306597126334236..., e^-1 = 0.3678794411714423215...,
//   e^-2 = 0.1353352832366126918..., e^-50 = 1.928749847963917783...e-22.
struct DecayCase {
  double dt_k;
  double decay;  // e^-(dt*k), by hand
};

class FrictionAtDtTimesK : public ::testing::TestWithParam<DecayCase> {
 protected:
  double dt_k() const { return GetParam().dt_k; }
  double rate() const { return dt_k() / kDt; }  // k such that dt*k = dt_k()
};

// e^-x as 1 / (sum of x^n/n!): the series has no cancellation for x >= 0, and
// uses no exp, so it checks the core's det::exp independently.
double exp_minus_by_series(double x) {
  double term = 1.0;
  double sum = 1.0;
  for (int n = 1; n < 400 && term > sum * 1e-18; ++n) {
    term *= x / n;
    sum += term;
  }
  return 1.0 / sum;
}

// rate()*kDt rounds back to dt*k within an ulp or two; exp turns that into a
// relative difference of about dt*k ulps, hence the relative bound 1e-13.
constexpr double kRounding = 1.0e-13;

// The core computes exp(-k*dt) with det::exp; the C library's std::exp restates it,
// and the hand value and the series stand beside it as the independent checks.
TEST_P(FrictionAtDtTimesK, DecayFactorIsExpOfMinusKDt) {
  const double factor = friction_decay_factor(rate(), kDt);
  const double hand = GetParam().decay;
  EXPECT_NEAR(factor, hand, kRounding * hand) << "against the hand value";
  const double series = exp_minus_by_series(dt_k());
  EXPECT_NEAR(series, hand, kRounding * hand) << "the series itself";
  EXPECT_NEAR(factor, series, kRounding * series) << "against the series";
  const double restated = std::exp(-dt_k());
  EXPECT_NEAR(factor, restated, kRounding * restated) << "against std::exp";
}

TEST_P(FrictionAtDtTimesK, EqualsExactDecayWithinRounding) {
  for (const double v : {10.0, -10.0, 1.0e-3, -123.456}) {
    const double expected = v * GetParam().decay;
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

INSTANTIATE_TEST_SUITE_P(HandPicked, FrictionAtDtTimesK,
                         ::testing::Values(DecayCase{0.5, 0.6065306597126334},
                                           DecayCase{1.0, 0.36787944117144233},
                                           DecayCase{2.0, 0.1353352832366127},
                                           DecayCase{50.0, 1.9287498479639178e-22}));

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

// Documentation of why the classic recipe's lerp(v, 0, t) is not used.
TEST(ClassicLerpFriction, OvershootsPastZeroAtOneAndAHalf) {
  EXPECT_EQ(lerp(10.0, 0.0, 1.5), -5.0);  // the velocity reversed
}

TEST(ClassicLerpFriction, DivergesPastTwo) {
  double v = 10.0;
  for (int step = 0; step < 20; ++step) v = lerp(v, 0.0, 2.5);  // factor (1-2.5) = -1.5
  EXPECT_GT(std::abs(v), 10.0 * 3000.0);                        // 1.5^20 = 3325.3
}

TEST(ClassicLerpFriction, AgreesWithExactDecayToFirstOrderForSmallDtK) {
  // For dt*k = 1e-3 the two differ by about (dt*k)^2/2 of v.
  const double lerp_value = lerp(10.0, 0.0, 1.0e-3);
  const double exact_value = apply_friction(10.0, 1.0e-3 / kDt, kDt);
  EXPECT_NEAR(lerp_value, exact_value, 10.0 * 1.0e-6);
  EXPECT_GT(std::abs(lerp_value - exact_value), 10.0 * 1.0e-7);
}

}  // namespace
}  // namespace phys
