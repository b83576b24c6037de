// Sensor overlaps between a circle and a box of unequal sides, and sensor overlaps
// carried through a world's bytes. A circle passes a flat sensor box across its
// thin side and a tall one beside its long side: each begins and ends at the steps
// the exact geometry gives. A world serialised while a body is inside a sensor, and
// restored from its bytes, ends that overlap when the body leaves, at the step the
// original world ends it, with no second begin.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

// 1/64 s steps of 4 sub-steps at 1 m/s: every position is a multiple of 1/256 m,
// exact in binary, so the steps of overlap can be counted by hand.
constexpr double kStep = 1.0 / 64.0;

WorldSettings weightless() {
  WorldSettings s;
  s.gravity = {0.0, 0.0};
  s.substeps = 4;
  return s;
}

std::vector<SensorEvent> run(World& world, int n) {
  std::vector<SensorEvent> seen;
  for (int i = 0; i < n; ++i) {
    world.step(kStep);
    seen.insert(seen.end(), world.sensor_events().begin(), world.sensor_events().end());
  }
  return seen;
}

BodyId add_sensor_box(World& world, Vec2 half) {
  BodyDef def = box_def({0.0, 0.0}, half, Motion::Static);
  def.is_sensor = true;
  return add_or_fail(world, def);
}

BodyId add_moving_circle(World& world, Vec2 at, Vec2 velocity) {
  BodyDef def = circle_def(at, 0.25);
  def.velocity = velocity;
  return add_or_fail(world, def);
}

TEST(SensorShapes, ACircleCrossingAFlatSensorBoxBeginsAndEndsWhereItsThinSideIs) {
  // A sensor 4 m wide and 0.25 m high; a circle of radius 0.25 rising through it
  // from y = -3 at 1 m/s: after step n its centre is at y = -3 + n/64. Their
  // interiors meet while |y| < 0.125 + 0.25: from n = 169 (y = -0.359) until
  // n = 216 (y = 0.375).
  World world(weightless());
  const BodyId sensor = add_sensor_box(world, {2.0, 0.125});
  const BodyId ball = add_moving_circle(world, {0.5, -3.0}, {0.0, 1.0});
  const std::vector<SensorEvent> seen = run(world, 300);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], (SensorEvent{SensorEventKind::Begin, 169, sensor, ball}));
  EXPECT_EQ(seen[1], (SensorEvent{SensorEventKind::End, 216, sensor, ball}));
}

TEST(SensorShapes, ACirclePassingBesideATallSensorBoxBeginsAndEndsWhereItsThinSideIs) {
  // A sensor 0.25 m wide and 4 m high; a circle of radius 0.25 at y = 1.5 (beside
  // the box's long side, inside its height) moving from x = -3 at 1 m/s: their
  // interiors meet while |x| < 0.375, from n = 169 until n = 216.
  World world(weightless());
  const BodyId sensor = add_sensor_box(world, {0.125, 2.0});
  const BodyId ball = add_moving_circle(world, {-3.0, 1.5}, {1.0, 0.0});
  const std::vector<SensorEvent> seen = run(world, 300);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], (SensorEvent{SensorEventKind::Begin, 169, sensor, ball}));
  EXPECT_EQ(seen[1], (SensorEvent{SensorEventKind::End, 216, sensor, ball}));
}

TEST(SensorShapes, AWorldRestoredFromBytesEndsTheOverlapItWasSavedWith) {
  // The circle rising through the flat sensor above, saved at step 190 (inside
  // since 169) and restored from its bytes: the restored world's only event is the
  // end at step 216, as the original's is.
  World world(weightless());
  const BodyId sensor = add_sensor_box(world, {2.0, 0.125});
  const BodyId ball = add_moving_circle(world, {0.5, -3.0}, {0.0, 1.0});
  const std::vector<SensorEvent> before = run(world, 190);
  ASSERT_EQ(before.size(), 1u);
  ASSERT_EQ(before[0].kind, SensorEventKind::Begin);
  ASSERT_EQ(world.sensor_overlaps(), 1u);

  std::string error;
  std::optional<World> restored = World::from_bytes(world.to_bytes(), &error);
  ASSERT_TRUE(restored.has_value()) << error;
  EXPECT_EQ(restored->sensor_overlaps(), 1u);
  EXPECT_EQ(restored->state_hash(), world.state_hash());

  const std::vector<SensorEvent> original_after = run(world, 60);
  const std::vector<SensorEvent> restored_after = run(*restored, 60);
  ASSERT_EQ(restored_after.size(), 1u);
  EXPECT_EQ(restored_after[0], (SensorEvent{SensorEventKind::End, 216, sensor, ball}));
  EXPECT_EQ(restored_after, original_after);
  EXPECT_EQ(restored->sensor_overlaps(), 0u);
}

}  // namespace
}  // namespace phys::testing
