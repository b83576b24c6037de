// The one box helper of the core and its users (vec2.h, body.h): a body's box from
// its shape, the box around a centre, and containment with edges included.
#include <gtest/gtest.h>

#include <limits>

#include "physics/body.h"
#include "physics/vec2.h"

namespace phys {
namespace {

TEST(Boxes, ACirclesHalfSizeIsItsRadiusOnBothAxes) {
  EXPECT_EQ(half_size(Shape::Circle, 0.25, {3.0, 4.0}), (Vec2{0.25, 0.25}));
  EXPECT_EQ(half_size(Shape::Box, 0.25, {3.0, 4.0}), (Vec2{3.0, 4.0}));
}

TEST(Boxes, TheBoxAroundACentreSpansItsHalfSizeEachWay) {
  const Aabb box = box_around({1.0, -2.0}, {0.5, 1.5});
  EXPECT_EQ(box.min, (Vec2{0.5, -3.5}));
  EXPECT_EQ(box.max, (Vec2{1.5, -0.5}));
}

TEST(Boxes, APointOnAnEdgeIsContainedAndOneJustOutsideIsNot) {
  const Aabb box{{0.0, 0.0}, {2.0, 1.0}};
  EXPECT_TRUE(contains(box, Vec2{0.0, 0.0}));
  EXPECT_TRUE(contains(box, Vec2{2.0, 1.0}));
  EXPECT_TRUE(contains(box, Vec2{1.0, 0.5}));
  EXPECT_FALSE(contains(box, Vec2{std::nextafter(2.0, 3.0), 0.5}));
  EXPECT_FALSE(contains(box, Vec2{1.0, std::nextafter(0.0, -1.0)}));
  EXPECT_FALSE(contains(box, Vec2{std::numeric_limits<double>::quiet_NaN(), 0.5}));
}

TEST(Boxes, ABoxIsContainedOnlyWhenBothCornersAre) {
  const Aabb outer{{0.0, 0.0}, {10.0, 10.0}};
  EXPECT_TRUE(contains(outer, outer));
  EXPECT_TRUE(contains(outer, Aabb{{1.0, 1.0}, {9.0, 9.0}}));
  EXPECT_FALSE(contains(outer, Aabb{{1.0, 1.0}, {10.5, 9.0}}));
  EXPECT_FALSE(contains(outer, Aabb{{-0.5, 1.0}, {9.0, 9.0}}));
}

}  // namespace
}  // namespace phys
