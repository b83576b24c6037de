// The restitution rules the step uses, against hand-computed values: a contact
// closing slower than the rest speed keeps no bounce, a faster one keeps the
// material's, and a pair's restitution is the larger of its two.
#include <gtest/gtest.h>

#include "physics/formulas.h"

namespace phys {
namespace {

constexpr double kRestSpeed = 0.01;

TEST(Restitution, BelowTheRestSpeedNothingBounces) {
  EXPECT_EQ(effective_restitution(0.005, 1.0, kRestSpeed), 0.0);
  EXPECT_EQ(effective_restitution(0.0, 0.5, kRestSpeed), 0.0);
}

TEST(Restitution, AtAndAboveTheRestSpeedTheMaterialBounces) {
  EXPECT_EQ(effective_restitution(kRestSpeed, 0.5, kRestSpeed), 0.5);
  EXPECT_EQ(effective_restitution(10.0, 1.0, kRestSpeed), 1.0);
  EXPECT_EQ(effective_restitution(10.0, 0.0, kRestSpeed), 0.0);
}

TEST(Restitution, MixingTakesTheLarger) {
  EXPECT_EQ(mix_restitution(0.2, 0.7), 0.7);
  EXPECT_EQ(mix_restitution(0.7, 0.2), 0.7);
  EXPECT_EQ(mix_restitution(0.0, 0.0), 0.0);
}

}  // namespace
}  // namespace phys
