// The narrowphase formulas against hand-computed values: circle-circle (overlap,
// exactly touching, apart), each of the four box separating conditions alone,
// the per-axis penetration, and circle-box through the closest point.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/formulas.h"

namespace phys {
namespace {

// ---- circle-circle ----

TEST(CollideCircles, OverlappingGivesPenetrationAndNormal) {
  // Centres 1.5 apart on x, radii 1 and 1: penetration |1.5 - 2| = 0.5, normal +x.
  const Contact c = collide_circles({0.0, 0.0}, 1.0, {1.5, 0.0}, 1.0);
  EXPECT_TRUE(c.colliding);
  EXPECT_DOUBLE_EQ(c.penetration, 0.5);
  EXPECT_DOUBLE_EQ(c.normal.x, 1.0);
  EXPECT_DOUBLE_EQ(c.normal.y, 0.0);
}

TEST(CollideCircles, NormalFollowsTheCentreLineOnADiagonal) {
  // A 3-4-5 triangle: distance 5, radii 3 + 3: penetration 1, normal (0.6, 0.8).
  const Contact c = collide_circles({1.0, 1.0}, 3.0, {4.0, 5.0}, 3.0);
  EXPECT_TRUE(c.colliding);
  EXPECT_DOUBLE_EQ(c.penetration, 1.0);
  EXPECT_DOUBLE_EQ(c.normal.x, 0.6);
  EXPECT_DOUBLE_EQ(c.normal.y, 0.8);
}

TEST(CollideCircles, ExactlyTouchingCountsAsColliding) {
  // distance 5 == 2.5 + 2.5 (exact in binary: sqrt(25) = 5).
  const Contact c = collide_circles({0.0, 0.0}, 2.5, {3.0, 4.0}, 2.5);
  EXPECT_TRUE(c.colliding);
  EXPECT_EQ(c.penetration, 0.0);
}

TEST(CollideCircles, ApartIsNotColliding) {
  EXPECT_FALSE(collide_circles({0.0, 0.0}, 2.0, {3.0, 4.0}, 2.0).colliding);  // 5 > 4
  EXPECT_FALSE(collide_circles({0.0, 0.0}, 1.0, {2.5, 0.0}, 1.0).colliding);  // 2.5 > 2
}

TEST(CollideCircles, SameCentreStillGivesAUnitNormal) {
  const Contact c = collide_circles({2.0, 2.0}, 1.0, {2.0, 2.0}, 0.5);
  EXPECT_TRUE(c.colliding);
  EXPECT_DOUBLE_EQ(c.penetration, 1.5);
  EXPECT_DOUBLE_EQ(length(c.normal), 1.0);
}

TEST(CollideCircles, TheEarlyOutAgreesWithTheSquareRootAtTheBoundary) {
  // collide_circles skips the square root for pairs whose squared distance is
  // well past the reach. Pairs within a few ulps of touching, on both sides, at
  // scales from 1e-150 to 1e150, must get exactly the answer of the plain formula
  // (distance = sqrt(d.d), colliding when distance <= r1 + r2).
  for (double scale : {1.0e-150, 1.0e-9, 1.0, 0.75, 3.0e4, 1.0e150}) {
    for (double angle = 0.0; angle < 6.3; angle += 0.37) {
      const double r1 = 0.5 * scale;
      const double r2 = 0.3 * scale;
      const Vec2 c1{1.0 * scale, -2.0 * scale};
      double distance = r1 + r2;
      for (int ulp = 0; ulp < 40; ++ulp) distance = std::nextafter(distance, 0.0);
      for (int step = 0; step < 80; ++step, distance = std::nextafter(distance, 1.0e300)) {
        const Vec2 c2 = c1 + Vec2{std::cos(angle), std::sin(angle)} * distance;
        const double plain = length(c2 - c1);
        const Contact c = collide_circles(c1, r1, c2, r2);
        ASSERT_EQ(c.colliding, plain <= r1 + r2) << "scale " << scale << " angle " << angle;
        if (c.colliding) {
          EXPECT_EQ(c.penetration, std::fabs(plain - r1 - r2));
        }
      }
    }
  }
}

// ---- box-box: the four separating conditions ----
// b is the box [-1, 1] x [-1, 1]; each `a` below satisfies exactly one condition.
constexpr Aabb kB{{-1.0, -1.0}, {1.0, 1.0}};

struct Separations {
  bool bottom_above_top, top_below_bottom, left_right_of_right, right_left_of_left;
};
Separations separations(const Aabb& a) {
  return {box_bottom_above_top(a, kB), box_top_below_bottom(a, kB), box_left_right_of_right(a, kB),
          box_right_left_of_left(a, kB)};
}

TEST(BoxSeparation, BottomAboveTopAlone) {
  const Aabb above{{-0.5, 1.5}, {0.5, 2.5}};
  const Separations s = separations(above);
  EXPECT_TRUE(s.bottom_above_top);
  EXPECT_FALSE(s.top_below_bottom);
  EXPECT_FALSE(s.left_right_of_right);
  EXPECT_FALSE(s.right_left_of_left);
  EXPECT_FALSE(boxes_intersect(above, kB));
}

TEST(BoxSeparation, TopBelowBottomAlone) {
  const Aabb below{{-0.5, -2.5}, {0.5, -1.5}};
  const Separations s = separations(below);
  EXPECT_FALSE(s.bottom_above_top);
  EXPECT_TRUE(s.top_below_bottom);
  EXPECT_FALSE(s.left_right_of_right);
  EXPECT_FALSE(s.right_left_of_left);
  EXPECT_FALSE(boxes_intersect(below, kB));
}

TEST(BoxSeparation, LeftRightOfRightAlone) {
  const Aabb right{{1.5, -0.5}, {2.5, 0.5}};
  const Separations s = separations(right);
  EXPECT_FALSE(s.bottom_above_top);
  EXPECT_FALSE(s.top_below_bottom);
  EXPECT_TRUE(s.left_right_of_right);
  EXPECT_FALSE(s.right_left_of_left);
  EXPECT_FALSE(boxes_intersect(right, kB));
}

TEST(BoxSeparation, RightLeftOfLeftAlone) {
  const Aabb left{{-2.5, -0.5}, {-1.5, 0.5}};
  const Separations s = separations(left);
  EXPECT_FALSE(s.bottom_above_top);
  EXPECT_FALSE(s.top_below_bottom);
  EXPECT_FALSE(s.left_right_of_right);
  EXPECT_TRUE(s.right_left_of_left);
  EXPECT_FALSE(boxes_intersect(left, kB));
}

TEST(BoxSeparation, NoConditionMeansIntersecting) {
  const Aabb overlapping{{0.5, 0.5}, {1.5, 1.5}};
  const Separations s = separations(overlapping);
  EXPECT_FALSE(s.bottom_above_top || s.top_below_bottom || s.left_right_of_right ||
               s.right_left_of_left);
  EXPECT_TRUE(boxes_intersect(overlapping, kB));
}

TEST(BoxSeparation, TouchingCountsAsIntersecting) {
  EXPECT_TRUE(boxes_intersect({{-0.5, 1.0}, {0.5, 2.0}}, kB));  // resting on top
  EXPECT_TRUE(boxes_intersect({{1.0, -0.5}, {2.0, 0.5}}, kB));  // against the right side
  EXPECT_TRUE(boxes_intersect({{1.0, 1.0}, {2.0, 2.0}}, kB));   // corner to corner
}

TEST(AxisPenetration, IsDistanceMinusHalfSizes) {
  // Centres 0 and 1.5, half sizes 1 and 1: |1.5 - 1 - 1| = 0.5, either order.
  EXPECT_DOUBLE_EQ(axis_penetration(0.0, 1.0, 1.5, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(axis_penetration(1.5, 1.0, 0.0, 1.0), 0.5);
  // Centres 3 and 2.25, half sizes 0.5 and 0.5: |0.75 - 1| = 0.25.
  EXPECT_DOUBLE_EQ(axis_penetration(3.0, 0.5, 2.25, 0.5), 0.25);
  // Touching: 0.
  EXPECT_EQ(axis_penetration(0.0, 1.0, 2.0, 1.0), 0.0);
}

// ---- circle-box ----

TEST(CollideCircleBox, AgainstAFace) {
  // Centre (0, 1.4), radius 0.5 over the top face y = 1: closest point (0, 1),
  // distance 0.4, penetration 0.1, normal from the circle toward the box: (0, -1).
  const Contact c = collide_circle_box({0.0, 1.4}, 0.5, kB);
  EXPECT_TRUE(c.colliding);
  EXPECT_NEAR(c.penetration, 0.1, 1e-15);
  EXPECT_DOUBLE_EQ(c.normal.x, 0.0);
  EXPECT_DOUBLE_EQ(c.normal.y, -1.0);
}

TEST(CollideCircleBox, AgainstACorner) {
  // Centre (1.3, 1.4), radius 1: closest point is the corner (1, 1), distance 0.5
  // along (0.3, 0.4): penetration 0.5, normal (-0.6, -0.8).
  const Contact c = collide_circle_box({1.3, 1.4}, 1.0, kB);
  EXPECT_TRUE(c.colliding);
  EXPECT_NEAR(c.penetration, 0.5, 1e-15);
  EXPECT_NEAR(c.normal.x, -0.6, 1e-15);
  EXPECT_NEAR(c.normal.y, -0.8, 1e-15);
}

TEST(CollideCircleBox, NearACornerButApart) {
  // Same centre, radius 0.4 < 0.5: the circle misses the corner although its
  // bounding box overlaps the box's.
  EXPECT_FALSE(collide_circle_box({1.3, 1.4}, 0.4, kB).colliding);
}

TEST(CollideCircleBox, ExactlyTouchingCountsAsColliding) {
  const Contact c = collide_circle_box({0.0, 1.5}, 0.5, kB);
  EXPECT_TRUE(c.colliding);
  EXPECT_EQ(c.penetration, 0.0);
}

TEST(CollideCircleBox, CentreInsideTheBoxIsPushedOutThroughTheNearestFace) {
  // Centre (0.9, 0) is 0.1 from the right face: the way out is +x, so the normal
  // (circle toward box) is -x and the penetration is radius + 0.1.
  const Contact c = collide_circle_box({0.9, 0.0}, 0.5, kB);
  EXPECT_TRUE(c.colliding);
  EXPECT_NEAR(c.penetration, 0.6, 1e-15);
  EXPECT_DOUBLE_EQ(c.normal.x, -1.0);
  EXPECT_DOUBLE_EQ(c.normal.y, 0.0);
}

}  // namespace
}  // namespace phys
