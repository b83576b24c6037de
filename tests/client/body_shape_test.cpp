// BodyShape::box_half_size: the box the viewer fits its camera to is the one the
// server sizes a body by (a circle's is (radius, radius)).
#include <gtest/gtest.h>

#include "client/types.h"

namespace {

TEST(BodyShape, ABoxOccupiesItsHalfExtents) {
  client::BodyShape box;
  box.shape = client::ShapeType::Box;
  box.half_extents = {1.5, 0.25};
  box.radius = 9.0;  // not a box's size
  EXPECT_EQ(box.box_half_size(), (client::Vec2{1.5, 0.25}));
}

TEST(BodyShape, ACircleOccupiesItsRadiusOnBothAxes) {
  client::BodyShape circle;
  circle.shape = client::ShapeType::Circle;
  circle.radius = 0.75;
  circle.half_extents = {4.0, 4.0};  // not a circle's size
  EXPECT_EQ(circle.box_half_size(), (client::Vec2{0.75, 0.75}));
}

}  // namespace
