// What the client library makes of a BodyShape's motion, velocity and filter, how it
// marks kinematic bodies in each snapshot, and its state hash against the worked
// example of docs/PROTOCOL.md 5.11.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "client/state_hash.h"
#include "convert.h"

namespace {

namespace pb = physics::wire;

TEST(KinematicShapes, AShapeSaysHowItMovesWithItsVelocityAndFilter) {
  pb::BodyShape lift;
  lift.set_body_id(7);
  lift.set_is_kinematic(true);
  lift.mutable_velocity()->set_x(0.5);
  lift.set_contact_friction(0.6);
  lift.set_category_bits(2);
  lift.set_group(-3);
  const client::BodyShape shape = client::convert::from_wire(lift);
  EXPECT_EQ(shape.motion, client::Motion::Kinematic);
  EXPECT_EQ(shape.velocity, (client::Vec2{0.5, 0.0}));
  EXPECT_EQ(shape.contact_friction, 0.6);
  // mask_bits absent: every bit, as phys::Filter's default.
  EXPECT_EQ(shape.filter, (client::CollisionFilter{2, 0xFFFFFFFFu, -3}));

  pb::BodyShape wall;
  wall.set_is_static(true);
  wall.set_mask_bits(0);  // present, and zero: told apart from absent
  const client::BodyShape still = client::convert::from_wire(wall);
  EXPECT_EQ(still.motion, client::Motion::Static);
  EXPECT_EQ(still.filter, (client::CollisionFilter{1, 0u, 0}));

  pb::BodyShape ball;
  ball.mutable_velocity()->set_x(-0.0);
  pb::BodyShape sent;  // through the bytes, as the server sends it
  ASSERT_TRUE(sent.ParseFromString(ball.SerializeAsString()));
  const client::BodyShape falling = client::convert::from_wire(sent);
  EXPECT_EQ(falling.motion, client::Motion::Dynamic);
  EXPECT_EQ(falling.filter, client::CollisionFilter{});
  EXPECT_TRUE(std::signbit(falling.velocity.x));  // -0.0 survives: the state hash tells it apart
}

TEST(KinematicShapes, EachBodyHeldIsMarkedKinematicOrDynamicAsItsShapeWas) {
  std::vector<std::uint64_t> kinematic;
  client::BodyShape lift;
  lift.body_id = 9;
  lift.motion = client::Motion::Kinematic;
  client::BodyShape ball;
  ball.body_id = 4;
  client::BodyShape pusher;
  pusher.body_id = 2;
  pusher.motion = client::Motion::Kinematic;
  client::convert::note_kinematic(kinematic, {lift, ball, pusher}, {});
  EXPECT_EQ(kinematic, (std::vector<std::uint64_t>{2, 9}));

  wire::Reconstruction held;
  pb::Snapshot snapshot;
  snapshot.set_tick(1);
  snapshot.set_full(true);
  for (const std::uint64_t id : {2u, 4u, 9u}) {
    pb::BodyState& b = *snapshot.add_bodies();
    b.set_body_id(id);
    b.set_x(static_cast<double>(id));
  }
  ASSERT_EQ(held.apply(snapshot, wire::Predictor(60.0, 0.0, -9.81), {}), "");
  std::vector<client::BodyState> bodies;
  client::convert::bodies_held(held, kinematic, bodies);
  ASSERT_EQ(bodies.size(), 3u);
  EXPECT_EQ(bodies[0].motion, client::Motion::Kinematic);
  EXPECT_EQ(bodies[1].motion, client::Motion::Dynamic);
  EXPECT_EQ(bodies[2].motion, client::Motion::Kinematic);
  EXPECT_EQ(bodies[2].position.x, 9.0);

  // A body removed is no longer marked.
  client::convert::note_kinematic(kinematic, {}, {9});
  EXPECT_EQ(kinematic, (std::vector<std::uint64_t>{2}));
}

// PROTOCOL.md 5.11's example: a static floor, then a dynamic circle with an input.
TEST(KinematicShapes, TheStateHashOfThePagesExample) {
  client::BodyShape floor;
  floor.body_id = 0x0000000100000000ull;
  floor.shape = client::ShapeType::Box;
  floor.motion = client::Motion::Static;
  floor.half_extents = {10.0, 0.5};
  floor.position = {0.0, -0.5};
  client::BodyShape circle;
  circle.body_id = 0x0000000100000001ull;
  circle.shape = client::ShapeType::Circle;
  circle.radius = 0.25;
  const client::BodyState moving{circle.body_id, {1.5, 2.0}, {3.0, 4.0}};
  const std::vector<client::KnownAcceleration> input{{circle.body_id, {0.0, 2.5}}};
  EXPECT_EQ(client::state_hash({circle, floor}, {moving}, input), 0x380d8cda1ab06e63ull);
  // The same acceleration as its shape's: the same hash.
  circle.acceleration = {0.0, 2.5};
  EXPECT_EQ(client::state_hash({floor, circle}, {moving}), 0x380d8cda1ab06e63ull);
  // A kinematic circle is another world; a moving body not held has no hash.
  circle.motion = client::Motion::Kinematic;
  EXPECT_NE(client::state_hash({floor, circle}, {moving}), 0x380d8cda1ab06e63ull);
  EXPECT_EQ(client::state_hash({floor, circle}, {}), std::nullopt);
}

}  // namespace
