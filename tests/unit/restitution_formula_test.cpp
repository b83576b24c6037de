// apply_restitution against hand-computed values: restitution 0, 0.5 and 1
// against a static body, the rest speed, separating contacts left alone, and two
// dynamic bodies of masses 1 and 3 splitting the impulse by inverse mass.
#include <gtest/gtest.h>

#include "physics/formulas.h"

namespace phys {
namespace {

// A ball (body 1) falling at 10 m/s onto a static floor (body 2, inverse mass 0);
// the normal points from the ball toward the floor: down.
constexpr Vec2 kDown{0.0, -1.0};
constexpr double kRestSpeed = 0.01;

Vec2 bounce_off_floor(Vec2 v, double restitution) {
  Vec2 floor_velocity{};
  apply_restitution(v, 1.0, floor_velocity, 0.0, kDown, restitution, kRestSpeed);
  EXPECT_EQ(floor_velocity, (Vec2{}));  // static bodies never move
  return v;
}

TEST(Restitution, ZeroStopsTheNormalSpeed) {
  EXPECT_EQ(bounce_off_floor({0.0, -10.0}, 0.0), (Vec2{0.0, 0.0}));
}

TEST(Restitution, HalfReflectsHalfTheSpeed) {
  EXPECT_EQ(bounce_off_floor({0.0, -10.0}, 0.5), (Vec2{0.0, 5.0}));
}

TEST(Restitution, OneKeepsTheSpeed) {
  EXPECT_EQ(bounce_off_floor({0.0, -10.0}, 1.0), (Vec2{0.0, 10.0}));
}

TEST(Restitution, TangentialVelocityIsKept) {
  EXPECT_EQ(bounce_off_floor({3.0, -10.0}, 0.5), (Vec2{3.0, 5.0}));
}

TEST(Restitution, BelowTheRestSpeedNothingBounces) {
  Vec2 v{0.0, -0.005};  // closing at 0.005 < rest speed 0.01
  Vec2 floor_velocity{};
  apply_restitution(v, 1.0, floor_velocity, 0.0, kDown, 1.0, kRestSpeed);
  EXPECT_EQ(v.y, 0.0);
}

TEST(Restitution, SeparatingBodiesAreLeftAlone) {
  Vec2 v{1.0, 4.0};  // already moving away from the floor
  Vec2 floor_velocity{};
  EXPECT_FALSE(apply_restitution(v, 1.0, floor_velocity, 0.0, kDown, 0.5, kRestSpeed));
  EXPECT_EQ(v, (Vec2{1.0, 4.0}));
}

TEST(Restitution, ApproachingReportsAChange) {
  Vec2 v{0.0, -10.0};
  Vec2 floor_velocity{};
  EXPECT_TRUE(apply_restitution(v, 1.0, floor_velocity, 0.0, kDown, 0.5, kRestSpeed));
}

TEST(Restitution, MixingTakesTheLarger) {
  EXPECT_EQ(mix_restitution(0.2, 0.7), 0.7);
  EXPECT_EQ(mix_restitution(0.7, 0.2), 0.7);
  EXPECT_EQ(mix_restitution(0.0, 0.0), 0.0);
}

// Masses 1 and 3 (inverse masses 1 and 1/3), head-on along +x: v1 = 2, v2 = -2.
// Momentum 1*2 + 3*(-2) = -4.
constexpr Vec2 kRight{1.0, 0.0};

TEST(MassSplit, ElasticCollisionOfMassesOneAndThree) {
  // e = 1: v1' = ((1-3)*2 + 2*3*(-2))/4 = -4, v2' = ((3-1)*(-2) + 2*1*2)/4 = 0.
  Vec2 v1{2.0, 0.0};
  Vec2 v2{-2.0, 0.0};
  apply_restitution(v1, 1.0, v2, 1.0 / 3.0, kRight, 1.0, kRestSpeed);
  EXPECT_NEAR(v1.x, -4.0, 1e-14);
  EXPECT_NEAR(v2.x, 0.0, 1e-14);
  EXPECT_NEAR(1.0 * v1.x + 3.0 * v2.x, -4.0, 1e-14);  // momentum conserved
}

TEST(MassSplit, PerfectlyInelasticMovesTogether) {
  // e = 0: both end at the centre-of-mass velocity -4/4 = -1.
  Vec2 v1{2.0, 0.0};
  Vec2 v2{-2.0, 0.0};
  apply_restitution(v1, 1.0, v2, 1.0 / 3.0, kRight, 0.0, kRestSpeed);
  EXPECT_NEAR(v1.x, -1.0, 1e-14);
  EXPECT_NEAR(v2.x, -1.0, 1e-14);
}

TEST(MassSplit, VelocityChangesAreInTheRatioOfInverseMasses) {
  // e = 0.5: the impulse j = (1 + e) * 4 / (1 + 1/3) = 4.5; dv1 = -4.5, dv2 = +1.5.
  Vec2 v1{2.0, 0.0};
  Vec2 v2{-2.0, 0.0};
  apply_restitution(v1, 1.0, v2, 1.0 / 3.0, kRight, 0.5, kRestSpeed);
  EXPECT_NEAR(v1.x - 2.0, -4.5, 1e-14);
  EXPECT_NEAR(v2.x + 2.0, 1.5, 1e-14);
  EXPECT_NEAR(1.0 * v1.x + 3.0 * v2.x, -4.0, 1e-14);
}

}  // namespace
}  // namespace phys
