// The predicting client shows kinematic bodies: render() lists every moving body,
// each with its motion, and a kinematic one where its velocity has taken it.
#include <gtest/gtest.h>

#include "client/prediction_core.h"
#include "physics/world.h"

namespace {

TEST(KinematicRender, RenderShowsTheLiftAsKinematicWhereItsVelocityTookIt) {
  phys::World world;
  phys::BodyDef floor;
  floor.motion = phys::Motion::Static;
  floor.half_extents = {10.0, 0.5};
  floor.position = {0.0, -0.5};
  phys::BodyDef lift;
  lift.motion = phys::Motion::Kinematic;
  lift.half_extents = {2.0, 0.25};
  lift.position = {-2.0, 3.0};
  lift.velocity = {0.5, 0.0};
  phys::BodyDef ball;
  ball.shape = phys::Shape::Circle;
  ball.radius = 0.25;
  ball.position = {5.0, 8.0};
  const phys::BodyId floor_id = world.add_body(floor);
  const phys::BodyId lift_id = world.add_body(lift);
  const phys::BodyId ball_id = world.add_body(ball);
  ASSERT_TRUE(floor_id.is_valid() && lift_id.is_valid() && ball_id.is_valid());

  client::PredictionCore core;
  core.start(std::move(world), 0, 0, 60.0);
  core.advance_to(20);
  ASSERT_EQ(core.predicted_tick(), 20u);
  const client::RenderState shown = core.render();
  ASSERT_EQ(shown.bodies.size(), 2u);  // the lift and the ball; the floor never moves
  const client::RenderBody& first = shown.bodies[0];
  const client::RenderBody& second = shown.bodies[1];
  EXPECT_EQ(first.body_id, lift_id.packed());
  EXPECT_EQ(first.motion, client::Motion::Kinematic);
  EXPECT_NEAR(first.position.x, -2.0 + 0.5 * 20.0 / 60.0, 1e-12);
  EXPECT_EQ(first.velocity, (client::Vec2{0.5, 0.0}));
  EXPECT_EQ(second.body_id, ball_id.packed());
  EXPECT_EQ(second.motion, client::Motion::Dynamic);
}

}  // namespace
