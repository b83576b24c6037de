// Sensors (BodyDef::is_sensor, physics/sensor_events.h): a box moved at a known
// velocity through a sensor begins and ends at the steps computed by hand, and
// moves exactly as in free motion (no impulse from the sensor); a falling sensor
// falls through the floor at free fall; filters choose what a sensor sees; events
// come in (sensor, visitor) order; a removal ends overlaps; no sensors, no events.
#include <gtest/gtest.h>

#include <vector>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

// 1/64 s steps of 4 sub-steps, at 1 m/s: every position is a multiple of 1/256 m,
// exact in binary, so the steps of overlap can be counted by hand.
constexpr double kStep = 1.0 / 64.0;

WorldSettings weightless() {
  WorldSettings s;
  s.gravity = {0.0, 0.0};
  s.substeps = 4;
  return s;
}

class Sensors : public WorldTest {
 protected:
  void SetUp() override { reset(weightless()); }
  void run(int n) {
    for (int i = 0; i < n; ++i) {
      world_.step(kStep);
      const auto& events = world_.sensor_events();
      seen_.insert(seen_.end(), events.begin(), events.end());
    }
  }
  BodyId add_sensor(BodyDef def) {
    def.is_sensor = true;
    return add(def);
  }
  std::vector<SensorEvent> seen_;
};

TEST_F(Sensors, AMovingBoxBeginsAndEndsAtTheStepsComputedByHand) {
  // A static sensor of half extents (1, 1) at the origin; a box of half extents
  // (0.25, 0.25) from x = -3 at 1 m/s: after step n its centre is at -3 + n/64.
  // Their interiors meet while |x| < 1.25: from x = -1.25 + 1/64 (n = 113, the
  // first step past x = -1.25), and no longer at x = 1.25 (n = 272).
  const BodyId sensor = add_sensor(box_def({0.0, 0.0}, {1.0, 1.0}, Motion::Static));
  BodyDef def = box_def({-3.0, 0.0}, {0.25, 0.25});
  def.velocity = {1.0, 0.0};
  const BodyId visitor = add(def);
  for (int n = 1; n <= 300; ++n) {
    run(1);
    // Free motion, exactly: the sensor applies no impulse and no correction.
    ASSERT_EQ(position(visitor).x, -3.0 + n / 64.0) << "step " << n;
    ASSERT_EQ(position(visitor).y, 0.0);
    ASSERT_EQ(velocity(visitor), (Vec2{1.0, 0.0}));
    EXPECT_EQ(world_.sensor_overlaps(), (n >= 113 && n < 272) ? 1u : 0u) << "step " << n;
  }
  ASSERT_EQ(seen_.size(), 2u);
  EXPECT_EQ(seen_[0], (SensorEvent{SensorEventKind::Begin, 113, sensor, visitor}));
  EXPECT_EQ(seen_[1], (SensorEvent{SensorEventKind::End, 272, sensor, visitor}));
}

TEST_F(Sensors, ACircleVisitorAndAKinematicSensorMeetAtTheHandComputedStep) {
  // A kinematic circle sensor of radius 1 from x = 4 at -1 m/s toward a resting
  // circle of radius 0.5 at the origin: centres 4 - n/64 apart, overlapping below
  // 1.5: from n = 161 (2.5 m later, strictly past 1.5 at 1.5 - 1/64), until the
  // sensor's centre is 1.5 beyond it, at x = -1.5 (n = 352).
  BodyDef s = circle_def({4.0, 0.0}, 1.0, Motion::Kinematic);
  s.velocity = {-1.0, 0.0};
  const BodyId sensor = add_sensor(s);
  const BodyId ball = add(circle_def({0.0, 0.0}, 0.5));
  run(400);
  ASSERT_EQ(seen_.size(), 2u);
  EXPECT_EQ(seen_[0], (SensorEvent{SensorEventKind::Begin, 161, sensor, ball}));
  EXPECT_EQ(seen_[1], (SensorEvent{SensorEventKind::End, 352, sensor, ball}));
  EXPECT_EQ(position(ball), (Vec2{0.0, 0.0}));  // never pushed
  EXPECT_EQ(velocity(ball), (Vec2{0.0, 0.0}));
}

TEST_F(Sensors, ADynamicSensorFallsThroughTheFloorAtFreeFall) {
  reset(WorldSettings{});
  const BodyId floor = make_floor(0.0);
  BodyDef def = box_def({0.0, 2.0}, {0.5, 0.5});
  const BodyId sensor = add_sensor(def);
  BodyDef free_def = def;
  free_def.position = {100.0, 2.0};  // the same body, far from anything
  const BodyId reference = add(free_def);
  for (int i = 0; i < 60; ++i) {
    world_.step(kDt);
    ASSERT_EQ(position(sensor).y, position(reference).y);
    ASSERT_EQ(velocity(sensor), velocity(reference));
  }
  EXPECT_LT(position(sensor).y, -2.0);
  (void)floor;
}

TEST_F(Sensors, FiltersChooseWhatASensorSees) {
  BodyDef s = box_def({0.0, 0.0}, {2.0, 2.0}, Motion::Static);
  s.filter.mask_bits = ~2u;  // blind to category 2
  const BodyId sensor = add_sensor(s);
  BodyDef hidden = box_def({0.0, 0.0}, {0.25, 0.25});
  hidden.filter.category_bits = 2;
  add(hidden);
  const BodyId seen = add(box_def({1.0, 0.0}, {0.25, 0.25}));
  // Sensors do not see each other.
  add_sensor(box_def({-1.0, 0.0}, {0.25, 0.25}));
  run(1);
  ASSERT_EQ(seen_.size(), 1u);
  EXPECT_EQ(seen_[0], (SensorEvent{SensorEventKind::Begin, 1, sensor, seen}));
}

TEST_F(Sensors, EventsComeInSensorThenVisitorOrderAndRemovalsEndThem) {
  const BodyId a = add(box_def({0.0, 0.0}, {0.25, 0.25}));
  const BodyId s2 = add_sensor(box_def({0.0, 0.0}, {1.0, 1.0}, Motion::Static));
  const BodyId b = add(box_def({0.5, 0.0}, {0.25, 0.25}));
  const BodyId s1 = add_sensor(box_def({0.5, 0.0}, {1.0, 1.0}, Motion::Static));
  run(1);
  const std::vector<SensorEvent> expected{
      {SensorEventKind::Begin, 1, s2, a},
      {SensorEventKind::Begin, 1, s2, b},
      {SensorEventKind::Begin, 1, s1, a},
      {SensorEventKind::Begin, 1, s1, b},
  };
  EXPECT_EQ(seen_, expected);
  seen_.clear();
  run(5);  // nothing changes, nothing is said
  EXPECT_TRUE(seen_.empty());
  ASSERT_TRUE(world_.remove_body(a));
  ASSERT_TRUE(world_.remove_body(s1));
  run(1);
  const std::vector<SensorEvent> ended{
      {SensorEventKind::End, 7, s2, a},
      {SensorEventKind::End, 7, s1, a},
      {SensorEventKind::End, 7, s1, b},
  };
  EXPECT_EQ(seen_, ended);
  EXPECT_EQ(world_.sensor_overlaps(), 1u);
  ASSERT_TRUE(world_.remove_body(s2));
  run(1);
  EXPECT_EQ(world_.sensor_overlaps(), 0u);
  run(1);
  EXPECT_TRUE(world_.sensor_events().empty());
}

TEST_F(Sensors, SensorsAreInTheStateHashOnlyWhereThereAreAny) {
  // The same bodies hash alike; a sensor flag changes the hash.
  World plain(weightless());
  World flagged(weightless());
  const BodyDef def = box_def({0.0, 0.0}, {1.0, 1.0}, Motion::Static);
  add_or_fail(plain, def);
  BodyDef sensor = def;
  sensor.is_sensor = true;
  add_or_fail(flagged, sensor);
  EXPECT_NE(plain.state_hash(), flagged.state_hash());
  World same(weightless());
  BodyDef named = def;
  named.name = "a label";  // names are not state
  add_or_fail(same, named);
  EXPECT_EQ(plain.state_hash(), same.state_hash());
}

}  // namespace
}  // namespace phys::testing
