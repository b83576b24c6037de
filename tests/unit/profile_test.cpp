// The step's profile (WorldSettings::profile): each phase of the recipe fills its
// own field, a phase that does not run leaves its field at zero, and with
// profiling off every field stays zero. Only which fields are filled is checked,
// never how long anything took.
#include <gtest/gtest.h>

#include "physics/world.h"
#include "scenes/scene_spec.h"
#include "scenes/scenes.h"

namespace phys::testing {
namespace {

StepProfile profile_of_a_pyramid(bool profile, bool contact_events) {
  WorldSettings settings;
  settings.profile = profile;
  World world(settings);
  world.set_contact_events(contact_events);
  scenes::add_to_world(world, scenes::pyramid_scene(10, 10));
  world.step(1.0 / 60.0);
  world.step(1.0 / 60.0);
  return world.last_profile();
}

TEST(StepProfile, EveryFieldStaysZeroWhenProfilingIsOff) {
  const StepProfile p = profile_of_a_pyramid(false, true);
  EXPECT_EQ(p.order_and_integrate, 0.0);
  EXPECT_EQ(p.candidates, 0.0);
  EXPECT_EQ(p.moves, 0.0);
  EXPECT_EQ(p.position_passes, 0.0);
  EXPECT_EQ(p.contact_events, 0.0);
  EXPECT_EQ(p.velocity_solver, 0.0);
  EXPECT_EQ(p.bounds_and_sleep, 0.0);
  EXPECT_EQ(p.total, 0.0);
}

TEST(StepProfile, EachPhaseFillsItsOwnField) {
  const StepProfile p = profile_of_a_pyramid(true, false);
  EXPECT_GT(p.order_and_integrate, 0.0);
  EXPECT_GT(p.candidates, 0.0);
  EXPECT_GT(p.moves, 0.0);
  EXPECT_GT(p.position_passes, 0.0);
  EXPECT_EQ(p.contact_events, 0.0) << "contact events are off";
  EXPECT_GT(p.velocity_solver, 0.0);
  EXPECT_GT(p.bounds_and_sleep, 0.0);
  EXPECT_GT(p.total, 0.0);
}

TEST(StepProfile, ContactEventsFillTheirField) {
  EXPECT_GT(profile_of_a_pyramid(true, true).contact_events, 0.0);
}

}  // namespace
}  // namespace phys::testing
