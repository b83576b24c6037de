// The world's queries (physics/query.h) on hand-made scenes, each answer computed by
// hand: what a ray, an overlap and a shape cast find, where and with which normal;
// hits exactly at a boundary and a hair beyond it; zero-length rays; casts from
// inside a body; filters and sensors; bad input refused; answers that follow the
// world as bodies come, go and move.
#include "physics/query.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A static box at (5, 0), 2 by 2: its faces at x = 4 and 6, y = -1 and 1.
class Queries : public ::testing::Test {
 protected:
  World world;
  BodyId box = add_or_fail(world, box_def({5.0, 0.0}, {1.0, 1.0}, Motion::Static));
};

void expect_hit(const std::optional<CastHit>& hit, BodyId body, double fraction, Vec2 point,
                Vec2 normal) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, body);
  EXPECT_EQ(hit->fraction, fraction);
  EXPECT_EQ(hit->point, point);
  EXPECT_EQ(hit->normal, normal);
}

TEST_F(Queries, RayMeetsTheNearFace) {
  expect_hit(world.cast_ray({0.0, 0.0}, {10.0, 0.0}), box, 0.4, {4.0, 0.0}, {-1.0, 0.0});
  expect_hit(world.cast_ray({5.0, 10.0}, {0.0, -10.0}), box, 0.9, {5.0, 1.0}, {0.0, 1.0});
  EXPECT_FALSE(world.cast_ray({0.0, 0.0}, {-10.0, 0.0}).has_value());  // pointing away
}

TEST_F(Queries, TouchingCountsAndAHairShortDoesNot) {
  // The face is reached exactly at the ray's end: fraction 1.
  expect_hit(world.cast_ray({0.0, 0.0}, {4.0, 0.0}), box, 1.0, {4.0, 0.0}, {-1.0, 0.0});
  EXPECT_FALSE(world.cast_ray({0.0, 0.0}, {std::nextafter(4.0, 0.0), 0.0}).has_value());
  // A ray along the top edge grazes it; one a hair above misses.
  expect_hit(world.cast_ray({0.0, 1.0}, {10.0, 0.0}), box, 0.4, {4.0, 1.0}, {-1.0, 0.0});
  EXPECT_FALSE(world.cast_ray({0.0, std::nextafter(1.0, 2.0)}, {10.0, 0.0}).has_value());
}

TEST_F(Queries, AnExactCornerTakesTheVerticalFacesNormal) {
  expect_hit(world.cast_ray({2.0, -3.0}, {4.0, 4.0}), box, 0.5, {4.0, -1.0}, {-1.0, 0.0});
}

TEST_F(Queries, RayTangentToACircleHitsIt) {
  const BodyId circle = add_or_fail(world, circle_def({5.0, 3.0}, 1.0, Motion::Static));
  expect_hit(world.cast_ray({0.0, 2.0}, {10.0, 0.0}), circle, 0.5, {5.0, 2.0}, {0.0, -1.0});
  EXPECT_FALSE(world.cast_ray({0.0, std::nextafter(2.0, 0.0)}, {10.0, 0.0}).has_value());
  expect_hit(world.cast_ray({0.0, 3.0}, {10.0, 0.0}), circle, 0.4, {4.0, 3.0}, {-1.0, 0.0});
}

TEST_F(Queries, ZeroLengthRayHitsNothingEvenInsideABody) {
  QueryError error = QueryError::TooLarge;
  EXPECT_FALSE(world.cast_ray({5.0, 0.0}, {0.0, 0.0}, {}, &error).has_value());
  EXPECT_EQ(error, QueryError::None);  // not refused: nothing to hit
  EXPECT_TRUE(world.cast_ray_all({5.0, 0.0}, {0.0, 0.0}).empty());
  EXPECT_FALSE(world.cast_circle({5.0, 0.0}, 1.0, {0.0, 0.0}).has_value());
  // A translation whose squared length underflows is none either: no NaN comes out.
  EXPECT_FALSE(world.cast_ray({0.0, 0.0}, {1.0e-200, 0.0}, {}, &error).has_value());
  EXPECT_EQ(error, QueryError::None);
  EXPECT_FALSE(world.cast_box({5.0, 0.0}, {1.0, 1.0}, {0.0, 1.0e-200}).has_value());
  EXPECT_FALSE(world.cast_ray({0.0, 0.0}, {1.0e-150, 0.0}).has_value());  // too short to reach
  // What is there is overlap_point's question.
  EXPECT_EQ(world.overlap_point({5.0, 0.0}), std::vector<BodyId>{box});
}

TEST_F(Queries, RayFromInsideHitsAtZeroOppositeTheRay) {
  expect_hit(world.cast_ray({5.0, 0.5}, {0.0, 10.0}), box, 0.0, {5.0, 0.5}, {0.0, -1.0});
  // On the boundary, leaving: touching at the start is inside.
  expect_hit(world.cast_ray({4.0, 0.0}, {-3.0, 0.0}), box, 0.0, {4.0, 0.0}, {1.0, 0.0});
  const BodyId beyond = add_or_fail(world, box_def({9.0, 0.0}, {1.0, 1.0}, Motion::Static));
  const std::vector<CastHit> all = world.cast_ray_all({5.0, 0.0}, {10.0, 0.0});
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].body, box);
  EXPECT_EQ(all[0].fraction, 0.0);
  EXPECT_EQ(all[1].body, beyond);
  EXPECT_EQ(all[1].fraction, 0.3);
}

TEST_F(Queries, AllHitsByFractionThenId) {
  // Two bodies entered at the same fraction: the lower id first.
  const BodyId upper = add_or_fail(world, box_def({2.0, 1.5}, {0.5, 0.5}, Motion::Static));
  const BodyId lower = add_or_fail(world, box_def({2.0, 0.5}, {0.5, 0.5}, Motion::Static));
  const std::vector<CastHit> all = world.cast_ray_all({0.0, 1.0}, {10.0, 0.0});
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].body, upper);
  EXPECT_EQ(all[1].body, lower);
  EXPECT_EQ(all[0].fraction, all[1].fraction);
  EXPECT_EQ(all[2].body, box);
  expect_hit(world.cast_ray({0.0, 1.0}, {10.0, 0.0}), upper, 0.15, {1.5, 1.0}, {-1.0, 0.0});
}

TEST_F(Queries, OverlapsCountTouching) {
  EXPECT_EQ(world.overlap_box({{0.0, 0.0}, {4.0, 0.5}}), std::vector<BodyId>{box});
  EXPECT_TRUE(world.overlap_box({{0.0, 0.0}, {std::nextafter(4.0, 0.0), 0.5}}).empty());
  EXPECT_EQ(world.overlap_circle({3.0, 0.0}, 1.0), std::vector<BodyId>{box});
  EXPECT_TRUE(world.overlap_circle({3.0, 0.0}, std::nextafter(1.0, 0.0)).empty());
  EXPECT_EQ(world.overlap_point({6.0, 1.0}), std::vector<BodyId>{box});  // a corner
  EXPECT_TRUE(world.overlap_point({6.0, std::nextafter(1.0, 2.0)}).empty());
  const BodyId circle = add_or_fail(world, circle_def({0.0, 5.0}, 2.0, Motion::Static));
  EXPECT_EQ(world.overlap_point({2.0, 5.0}), std::vector<BodyId>{circle});
  EXPECT_EQ(world.overlap_circle({0.0, 8.0}, 1.0), std::vector<BodyId>{circle});
  EXPECT_EQ(world.overlap_box({{2.0, 4.0}, {3.0, 6.0}}), std::vector<BodyId>{circle});
  EXPECT_EQ(world.overlap_box({{-10.0, -10.0}, {10.0, 10.0}}), (std::vector<BodyId>{box, circle}));
}

TEST_F(Queries, CircleCastMeetsFacesCornersAndCircles) {
  expect_hit(world.cast_circle({0.0, 0.0}, 0.5, {10.0, 0.0}), box, 0.35, {4.0, 0.0}, {-1.0, 0.0});
  // Grazing the top edge: the first touch is the corner (4, 1).
  expect_hit(world.cast_circle({0.0, 2.0}, 1.0, {10.0, 0.0}), box, 0.4, {4.0, 1.0}, {0.0, 1.0});
  EXPECT_FALSE(world.cast_circle({0.0, std::nextafter(2.0, 3.0)}, 1.0, {10.0, 0.0}).has_value());
  const BodyId circle = add_or_fail(world, circle_def({5.0, 10.0}, 1.0, Motion::Static));
  expect_hit(world.cast_circle({0.0, 10.0}, 1.0, {10.0, 0.0}), circle, 0.3, {4.0, 10.0},
             {-1.0, 0.0});
  // Starting in touch: fraction 0 at the centre.
  expect_hit(world.cast_circle({3.0, 0.0}, 1.0, {0.0, 1.0}), box, 0.0, {3.0, 0.0}, {0.0, -1.0});
}

TEST_F(Queries, BoxCastMeetsBoxesAndCircles) {
  expect_hit(world.cast_box({0.0, 0.0}, {0.5, 0.5}, {10.0, 0.0}), box, 0.35, {4.0, 0.0},
             {-1.0, 0.0});
  // Level with the top face: it slides along it and touches the box's corner.
  expect_hit(world.cast_box({0.0, 1.5}, {0.5, 0.5}, {10.0, 0.0}), box, 0.35, {4.0, 1.0},
             {-1.0, 0.0});
  EXPECT_FALSE(
      world.cast_box({0.0, std::nextafter(1.5, 2.0)}, {0.5, 0.5}, {10.0, 0.0}).has_value());
  const BodyId circle = add_or_fail(world, circle_def({5.0, 10.0}, 1.0, Motion::Static));
  expect_hit(world.cast_box({0.0, 10.0}, {1.0, 1.0}, {10.0, 0.0}), circle, 0.3, {4.0, 10.0},
             {-1.0, 0.0});
}

TEST_F(Queries, FiltersAndSensorsAreHonoured) {
  BodyDef sensor = box_def({2.0, 0.0}, {0.5, 0.5}, Motion::Static);
  sensor.is_sensor = true;
  const BodyId sensor_id = add_or_fail(world, sensor);
  BodyDef tagged = box_def({3.0, 0.0}, {0.25, 0.25}, Motion::Static);
  tagged.filter.category_bits = 0x4;
  const BodyId tagged_id = add_or_fail(world, tagged);

  EXPECT_EQ(world.cast_ray({0.0, 0.0}, {10.0, 0.0})->body, tagged_id);  // the sensor skipped
  QueryFilter with_sensors;
  with_sensors.include_sensors = true;
  EXPECT_EQ(world.cast_ray({0.0, 0.0}, {10.0, 0.0}, with_sensors)->body, sensor_id);
  QueryFilter not_tagged;
  not_tagged.filter = Filter{0x1, ~0x4u, 0};
  EXPECT_EQ(world.cast_ray({0.0, 0.0}, {10.0, 0.0}, not_tagged)->body, box);
  QueryFilter only_tagged;
  only_tagged.filter = Filter{0x1, 0x4u, 0};
  EXPECT_EQ(world.overlap_box({{-10.0, -10.0}, {10.0, 10.0}}, only_tagged),
            std::vector<BodyId>{tagged_id});
  EXPECT_EQ(world.overlap_box({{-10.0, -10.0}, {10.0, 10.0}}, with_sensors),
            (std::vector<BodyId>{box, sensor_id, tagged_id}));
  // A body that meets nothing (mask 0) is still found by an unfiltered query.
  ASSERT_TRUE(world.set_filter(box, Filter{0x1, 0x0, 0}));
  EXPECT_EQ(world.overlap_point({5.0, 0.0}), std::vector<BodyId>{box});
  EXPECT_TRUE(world.overlap_point({5.0, 0.0}, not_tagged).empty());
}

TEST_F(Queries, BadInputIsRefused) {
  QueryError error = QueryError::None;
  const auto refused = [&](auto answer, QueryError expected) {
    bool empty = false;
    if constexpr (requires { answer.has_value(); }) {
      empty = !answer.has_value();
    } else {
      empty = answer.empty();
    }
    EXPECT_TRUE(empty);
    EXPECT_EQ(error, expected) << describe(error);
    error = QueryError::None;
  };
  refused(world.cast_ray({kNaN, 0.0}, {1.0, 0.0}, {}, &error), QueryError::NonFinite);
  refused(world.cast_ray({0.0, 0.0}, {kInf, 0.0}, {}, &error), QueryError::NonFinite);
  refused(world.cast_ray({0.0, 0.0}, {1.0e13, 0.0}, {}, &error), QueryError::TooLarge);
  refused(world.cast_ray_all({0.0, kNaN}, {1.0, 0.0}, {}, &error), QueryError::NonFinite);
  refused(world.overlap_box({{-kInf, -kInf}, {kInf, kInf}}, {}, &error), QueryError::NonFinite);
  refused(world.overlap_box({{1.0, 0.0}, {0.0, 1.0}}, {}, &error), QueryError::InvertedBox);
  refused(world.overlap_box({{0.0, -2.0e12}, {1.0, 1.0}}, {}, &error), QueryError::TooLarge);
  refused(world.overlap_circle({5.0, 0.0}, -1.0, {}, &error), QueryError::NegativeSize);
  refused(world.overlap_circle({5.0, 0.0}, kNaN, {}, &error), QueryError::NonFinite);
  refused(world.overlap_point({kInf, 0.0}, {}, &error), QueryError::NonFinite);
  refused(world.cast_circle({0.0, 0.0}, -0.5, {10.0, 0.0}, {}, &error), QueryError::NegativeSize);
  refused(world.cast_box({0.0, 0.0}, {1.0, -1.0}, {10.0, 0.0}, {}, &error),
          QueryError::NegativeSize);
  refused(world.cast_box({0.0, 0.0}, {1.0, 1.0}, {10.0, kNaN}, {}, &error), QueryError::NonFinite);
  // Refusals have a description each; a good query says None.
  EXPECT_NE(describe(QueryError::InvertedBox), describe(QueryError::NonFinite));
  error = QueryError::TooLarge;
  EXPECT_TRUE(world.cast_ray({0.0, 0.0}, {10.0, 0.0}, {}, &error).has_value());
  EXPECT_EQ(error, QueryError::None);
}

TEST_F(Queries, AnswersFollowTheWorld) {
  // Queried once (the grids made), then changed: each answer is the new world's.
  EXPECT_EQ(world.cast_ray({0.0, 0.0}, {10.0, 0.0})->body, box);
  const BodyId near = add_or_fail(world, circle_def({2.0, 0.0}, 0.5, Motion::Static));
  EXPECT_EQ(world.cast_ray({0.0, 0.0}, {10.0, 0.0})->body, near);
  ASSERT_TRUE(world.remove_body(near));
  EXPECT_EQ(world.cast_ray({0.0, 0.0}, {10.0, 0.0})->body, box);

  WorldSettings floating;
  floating.gravity = {0.0, -10.0};
  World falling(floating);
  const BodyId ball = add_or_fail(falling, circle_def({0.0, 10.0}, 0.5));
  EXPECT_EQ(falling.overlap_point({0.0, 10.0}), std::vector<BodyId>{ball});
  ASSERT_TRUE(falling.set_position(ball, {3.0, 10.0}));
  EXPECT_TRUE(falling.overlap_point({0.0, 10.0}).empty());
  EXPECT_EQ(falling.overlap_point({3.0, 10.0}), std::vector<BodyId>{ball});
  const SavedWorld saved = falling.save();
  for (int i = 0; i < 30; ++i) falling.step(kDt);
  const double y = falling.body(ball)->position.y;
  ASSERT_LT(y, 9.0);
  EXPECT_TRUE(falling.overlap_point({3.0, 10.0}).empty());
  EXPECT_EQ(falling.overlap_point({3.0, y}), std::vector<BodyId>{ball});
  falling.restore(saved);
  EXPECT_EQ(falling.overlap_point({3.0, 10.0}), std::vector<BodyId>{ball});
}

TEST_F(Queries, ResultsAreValuesTheCallerMayActOn) {
  // Rules that add a body for every body found, while going through the answer.
  for (int i = 0; i < 4; ++i)
    add_or_fail(world, box_def({5.0, 3.0 + i}, {0.4, 0.4}, Motion::Static));
  const std::vector<BodyId> found = world.overlap_box({{4.0, -2.0}, {6.0, 10.0}});
  ASSERT_EQ(found.size(), 5u);
  for (const BodyId id : found) {
    add_or_fail(world, circle_def(world.body(id)->position + Vec2{10.0, 0.0}, 0.3, Motion::Static));
  }
  EXPECT_EQ(world.overlap_box({{14.0, -2.0}, {16.0, 10.0}}).size(), 5u);
}

}  // namespace
}  // namespace phys::testing
