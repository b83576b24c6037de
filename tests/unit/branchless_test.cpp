// The branchless clamp of the contact solver must give std::max's answer bit for
// bit, or the golden state hash would depend on whether the build has SSE2.
#include "branchless.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace phys {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

TEST(AtLeastZero, MatchesStdMaxBitForBitOnEdgeValues) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> values = {0.0,
                                      -0.0,
                                      1.0,
                                      -1.0,
                                      std::numeric_limits<double>::denorm_min(),
                                      -std::numeric_limits<double>::denorm_min(),
                                      std::numeric_limits<double>::max(),
                                      std::numeric_limits<double>::lowest(),
                                      inf,
                                      -inf,
                                      std::numeric_limits<double>::quiet_NaN(),
                                      -std::numeric_limits<double>::quiet_NaN()};
  for (double x : values) {
    EXPECT_EQ(bits(at_least_zero(x)), bits(std::max(x, 0.0))) << "x = " << x;
  }
}

TEST(AtLeastZero, MatchesStdMaxOnImpulseSizedValues) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> impulse(-10.0, 10.0);
  for (int i = 0; i < 100000; ++i) {
    const double x = impulse(random);
    ASSERT_EQ(bits(at_least_zero(x)), bits(std::max(x, 0.0))) << "x = " << x;
  }
}

}  // namespace
}  // namespace phys
