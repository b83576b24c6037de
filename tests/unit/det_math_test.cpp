// The step's own exp, expm1 and log (physics/det_math.h) against the C library's,
// a million points in each range the core uses, with the largest error in ulps
// (units in the last place of the C library's result) stated and asserted:
//   exp(x)    x in [-50, 0]         (friction's decay e^(-k dt), k dt up to 50)
//             x in [-1e-3, 0]       (the integrator's series branch, k t < 1e-3)
//             x in [-745, 709]      (every finite, non-zero result)        <= 1 ulp
//   expm1(x)  x in [-ln2/2, 0]      (the integrator's phi1 at k t >= 1e-3)
//             x in [-40, -1e-3]                                            <= 1 ulp
//             x in [-40, 709]       (positive arguments too)              <= 2 ulp
//   log(x)    x in (0, 1)           (the sweep's turning point, e^(-k t))
//             x log-uniform in [2^-1074, 1)                               <= 1 ulp
// glibc's are within 1 ulp of the exact values, so ours are within 2 (3 for
// positive expm1). Special values follow the C library.
#include "physics/det_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>

namespace phys::det {
namespace {

constexpr int kPoints = 1'000'000;

// |got - want| in units of want's last place.
double ulps(double got, double want) {
  if (got == want) return 0.0;
  const double magnitude = std::fabs(want);
  const double ulp = std::nextafter(magnitude, std::numeric_limits<double>::infinity()) - magnitude;
  return std::fabs(got - want) / ulp;
}

// xorshift64: the same points on every run.
struct Points {
  std::uint64_t state = 0x9e3779b97f4a7c15ULL;
  double unit() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<double>(state >> 11) * 0x1p-53;
  }
};

struct Worst {
  double ulps = 0.0;
  double at = 0.0;
  int differing = 0;  // points whose result differs from the C library's at all
};

Worst worst_over(const std::function<double(double)>& ours, double (*libc)(double),
                 const std::function<double(double)>& point_from_unit) {
  Points points;
  Worst worst;
  for (int i = 0; i < kPoints; ++i) {
    const double x = point_from_unit(points.unit());
    const double error = ulps(ours(x), libc(x));
    if (error > 0.0) ++worst.differing;
    if (error > worst.ulps) worst = {error, x, worst.differing};
  }
  return worst;
}

std::function<double(double)> uniform(double lo, double hi) {
  return [lo, hi](double u) { return lo + (hi - lo) * u; };
}

double libc_exp(double x) { return std::exp(x); }
double libc_expm1(double x) { return std::expm1(x); }
double libc_log(double x) { return std::log(x); }
double our_exp(double x) { return exp(x); }
double our_expm1(double x) { return expm1(x); }
double our_log(double x) { return log(x); }

void expect_within(const Worst& worst, double bound, const char* what) {
  EXPECT_LE(worst.ulps, bound) << what << ": " << worst.ulps << " ulp at x = " << worst.at;
  std::printf("%s: max %.0f ulp, %d of %d points differ from the C library's\n", what, worst.ulps,
              worst.differing, kPoints);
}

TEST(DetMath, ExpWithinOneUlpOverFrictionDecays) {
  expect_within(worst_over(our_exp, libc_exp, uniform(-50.0, 0.0)), 1.0, "exp [-50, 0]");
}

TEST(DetMath, ExpWithinOneUlpOverTheSeriesBranch) {
  expect_within(worst_over(our_exp, libc_exp, uniform(-1.0e-3, 0.0)), 1.0, "exp [-1e-3, 0]");
}

TEST(DetMath, ExpWithinOneUlpOverEveryFiniteResult) {
  expect_within(worst_over(our_exp, libc_exp, uniform(-745.0, 709.0)), 1.0, "exp [-745, 709]");
}

TEST(DetMath, Expm1WithinOneUlpOverTheReducedRange) {
  const double half_ln2 = 0.5 * std::log(2.0);
  expect_within(worst_over(our_expm1, libc_expm1, uniform(-half_ln2, 0.0)), 1.0,
                "expm1 [-ln2/2, 0]");
}

TEST(DetMath, Expm1WithinOneUlpOverNegativeArguments) {
  expect_within(worst_over(our_expm1, libc_expm1, uniform(-40.0, -1.0e-3)), 1.0,
                "expm1 [-40, -1e-3]");
}

TEST(DetMath, Expm1WithinTwoUlpOverPositiveArgumentsToo) {
  expect_within(worst_over(our_expm1, libc_expm1, uniform(-40.0, 709.0)), 2.0, "expm1 [-40, 709]");
}

TEST(DetMath, LogWithinOneUlpOverTheUnitInterval) {
  expect_within(worst_over(our_log, libc_log, [](double u) { return u > 0.0 ? u : 0.5; }), 1.0,
                "log (0, 1)");
}

TEST(DetMath, LogWithinOneUlpOverEveryBinadeBelowOne) {
  // About 2^(-1074 u): subnormals included.
  const auto log_uniform = [](double u) {
    return std::ldexp(0.5 * (1.0 + u), -static_cast<int>(1073 * u));
  };
  expect_within(worst_over(our_log, libc_log, log_uniform), 1.0, "log [2^-1074, 1)");
}

TEST(DetMath, SpecialValuesFollowTheCLibrary) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(exp(0.0), 1.0);
  EXPECT_EQ(exp(-inf), 0.0);
  EXPECT_EQ(exp(inf), inf);
  EXPECT_EQ(exp(710.0), inf);
  EXPECT_EQ(exp(-746.0), 0.0);
  EXPECT_TRUE(std::isnan(exp(nan)));
  EXPECT_EQ(expm1(0.0), 0.0);
  EXPECT_EQ(expm1(1.0e-300), 1.0e-300);
  EXPECT_EQ(expm1(-inf), -1.0);
  EXPECT_EQ(expm1(inf), inf);
  EXPECT_TRUE(std::isnan(expm1(nan)));
  EXPECT_EQ(log(1.0), 0.0);
  EXPECT_EQ(log(0.0), -inf);
  EXPECT_EQ(log(inf), inf);
  EXPECT_TRUE(std::isnan(log(-1.0)));
  EXPECT_TRUE(std::isnan(log(nan)));
  EXPECT_EQ(log(std::numeric_limits<double>::denorm_min()),
            std::log(std::numeric_limits<double>::denorm_min()));
  // Subnormal results of exp: rounded once, as the C library does.
  EXPECT_EQ(exp(-740.0), std::exp(-740.0));
}

}  // namespace
}  // namespace phys::det
