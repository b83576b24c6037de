// World settings out of their ranges are refused, naming the setting; the settings
// a scene gives are carried into the definition, and the ones it leaves out keep
// their defaults.
#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::accepted;
using testing::kSpawn;
using testing::refused;

TEST(BadScene, WorldSettingsOutOfRangeAreRefused) {
  struct Case {
    const char* world;
    const char* field;
  };
  for (const Case& c : {
           Case{"tick_rate: 0", "world.tick_rate"},
           Case{"tick_rate: -60", "world.tick_rate"},
           Case{"tick_rate: 5000", "world.tick_rate"},
           Case{"steps_per_frame: 0", "world.steps_per_frame"},
           Case{"slop: -1", "world.slop"},
           Case{"slop: 5", "world.slop"},
           Case{"substeps: 0", "world.substeps"},
           Case{"substeps: 1000", "world.substeps"},
           Case{"position_iterations: 0", "world.position_iterations"},
           Case{"velocity_iterations: 100000", "world.velocity_iterations"},
           Case{"max_acceleration: 0", "world.max_acceleration"},
           Case{"max_speed: -1", "world.max_speed"},
           Case{"sleep_time: -1", "world.sleep_time"},
           Case{"rest_speed: nan", "world.rest_speed"},
           Case{"bounds { min { x: 1 y: 0 } max { x: 1 y: 5 } }", "world.bounds.max.x"},
           Case{"bounds { min { x: 0 y: 5 } max { x: 1 y: 0 } }", "world.bounds.max.y"},
           Case{"integrator: 7", "world.integrator"},
       }) {
    SCOPED_TRACE(c.world);
    const SceneError error =
        refused(std::string("world {\n  ") + c.world + "\n}\n" + std::string(kSpawn));
    EXPECT_EQ(error.field, c.field) << error.to_string();
  }
}

TEST(BadScene, WorldSettingsAreCarriedOver) {
  const SceneDef def = accepted(
      "world { gravity { x: 1 y: 2 } tick_rate: 120 steps_per_frame: 3 slop: 0.001\n"
      "  max_acceleration: 20 integrator: INTEGRATOR_SEMI_IMPLICIT_EULER substeps: 4\n"
      "  position_iterations: 8 velocity_iterations: 2 continuous: false sleeping: false\n"
      "  shock_propagation: false hold_resting_support: false }\n" +
      std::string(kSpawn));
  EXPECT_EQ(def.world.gravity, (phys::Vec2{1, 2}));
  EXPECT_EQ(def.tick_rate, 120.0);
  EXPECT_EQ(def.steps_per_frame, 3);
  EXPECT_EQ(def.world.slop, 0.001);
  EXPECT_EQ(def.max_acceleration, 20.0);
  EXPECT_EQ(def.world.integrator, phys::Integrator::SemiImplicitEuler);
  EXPECT_EQ(def.world.substeps, 4);
  EXPECT_EQ(def.world.position_iterations, 8);
  EXPECT_EQ(def.world.velocity_iterations, 2);
  EXPECT_FALSE(def.world.continuous);
  EXPECT_FALSE(def.world.sleeping);
  EXPECT_FALSE(def.world.shock_propagation);
  EXPECT_FALSE(def.world.hold_resting_support);
  EXPECT_FALSE(def.world.has_bounds);
  // Explicit zero gravity differs from unset (the default, -9.81 down).
  EXPECT_EQ(accepted("world { gravity { } }\n" + std::string(kSpawn)).world.gravity,
            (phys::Vec2{0, 0}));
  EXPECT_EQ(accepted(std::string(kSpawn)).world.gravity, phys::WorldSettings{}.gravity);
}

}  // namespace
}  // namespace scene
