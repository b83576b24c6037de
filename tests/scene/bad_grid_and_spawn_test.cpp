// Grids, the player's template and spawn points: too many bodies are refused before
// anything is allocated, a grid's faults name the grid, a grid places its rows as
// written, and the player must be a dynamic template that fits at every spawn point.
#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::accepted;
using testing::kWorld;
using testing::refused;
using testing::scene_with;

TEST(BadScene, SpawnPointOutOfBoundsIsRefused) {
  const SceneError error = refused(std::string(kWorld) + "spawn_points { x: 1 y: 1 }\n" +
                                   "spawn_points { x: 20 y: 1 }\n");
  EXPECT_EQ(error.field, "spawn_points[1]");
  EXPECT_EQ(error.line, 3);
}

TEST(BadScene, NoSpawnPointsIsRefused) {
  const SceneError error = refused(std::string(kWorld) + "bodies { circle { radius: 1 } }\n");
  EXPECT_EQ(error.field, "spawn_points");
  EXPECT_NE(error.message.find("no spawn points"), std::string::npos);
}

TEST(BadScene, HugeGridIsRefusedBeforeAllocating) {
  const SceneError error =
      refused(scene_with("grids {\n"
                         "  body { circle { radius: 0.1 } }\n"
                         "  count_x: 1000000000\n"
                         "  count_y: 1000000000\n"
                         "}\n"));
  EXPECT_EQ(error.field, "grids[0].count_x");
  EXPECT_EQ(error.line, 4);
  // Each count within range, but together too many: refused as a whole grid.
  const SceneError together =
      refused(scene_with("grids { body { circle { radius: 0.001 } } spacing { x: 0.001 y: 0.001 } "
                         "count_x: 1000000 count_y: 1000000 }\n"));
  EXPECT_EQ(together.field, "grids[0]");
  EXPECT_NE(together.message.find("limit"), std::string::npos) << together.message;
  // Two grids that are each allowed but exceed the limit together.
  const std::string half =
      "grids { body { circle { radius: 0.001 } } spacing { x: 0.001 y: 0.001 } "
      "count_x: 1000 count_y: 600 }\n";
  EXPECT_EQ(refused(scene_with(half + half)).field, "grids[1]");
}

TEST(BadScene, GridProblemsNameTheGrid) {
  EXPECT_EQ(refused(scene_with("grids { count_x: 2 count_y: 2 }\n")).field, "grids[0].body");
  EXPECT_EQ(
      refused(scene_with("grids { body { circle { radius: 1 } } count_x: 0 count_y: 2 }\n")).field,
      "grids[0].count_x");
  EXPECT_EQ(
      refused(scene_with("grids { body { circle { radius: -1 } } count_x: 1 count_y: 1 }\n")).field,
      "grids[0].body.circle.radius");
  EXPECT_EQ(refused(scene_with("grids { body { circle { radius: 1 } position { x: 1 } } "
                               "count_x: 1 count_y: 1 }\n"))
                .field,
            "grids[0].body.position");
  const SceneError outside = refused(scene_with(
      "grids { body { circle { radius: 0.5 } } origin { x: 0 y: 0 } spacing { x: 1 y: 1 } "
      "count_x: 20 count_y: 1 }\n"));
  EXPECT_EQ(outside.field, "grids[0]");
  EXPECT_NE(outside.message.find("column 10"), std::string::npos) << outside.message;
}

TEST(BadScene, GridPlacesRowsWithTaperAndStagger) {
  const SceneDef pyramid = accepted(
      scene_with("grids { body { box { half_extents { x: 0.5 y: 0.5 } } } origin { x: -2 y: 0 }\n"
                 "  spacing { x: 1 y: 1 } count_x: 3 count_y: 5 taper: 1 }\n"));
  ASSERT_EQ(pyramid.bodies.size(), 6u) << "rows of 3, 2 and 1; rows of 0 are left out";
  EXPECT_EQ(pyramid.bodies[3].position, (phys::Vec2{-1.5, 1}));
  EXPECT_EQ(pyramid.bodies[5].position, (phys::Vec2{-1, 2}));
  const SceneDef staggered = accepted(scene_with(
      "grids { body { circle { radius: 0.25 } } spacing { x: 1 y: 1 } count_x: 2 count_y: 2 "
      "stagger: true }\n"));
  ASSERT_EQ(staggered.bodies.size(), 4u);
  EXPECT_EQ(staggered.bodies[1].position, (phys::Vec2{1, 0}));
  EXPECT_EQ(staggered.bodies[2].position, (phys::Vec2{0.5, 1}));
}

TEST(BadScene, PlayerMustBeADynamicTemplate) {
  EXPECT_EQ(refused(scene_with("player { circle { radius: 1 } is_static: true }\n")).field,
            "player.is_static");
  EXPECT_EQ(refused(scene_with("player { circle { radius: 1 } position { x: 1 } }\n")).field,
            "player.position");
  EXPECT_EQ(refused(scene_with("player { box { half_extents { x: 0 y: 1 } } }\n")).field,
            "player.box.half_extents.x");
  // A player too large for the room at a spawn point is refused at that point.
  EXPECT_EQ(refused(scene_with("player { circle { radius: 9.5 } }\n")).field, "spawn_points[0]");
}

}  // namespace
}  // namespace scene
