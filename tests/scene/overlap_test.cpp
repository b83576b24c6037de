// Bodies that start inside one another are refused with the file, line and column of
// the later one; touching bodies, bodies apart, and two static bodies overlapping
// are accepted (docs/SCENES.md, "Errors"). That every example scene is apart is
// ExampleScenes.EveryFileInScenesLoadsAndBuilds.
#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::accepted;
using testing::refused;
using testing::scene_with;

TEST(Overlap, TwoCirclesInsideOneAnotherAreRefusedAtTheLaterOne) {
  const SceneError error =
      refused(scene_with("bodies { circle { radius: 1 } position { x: 0 y: 0 } }\n"
                         "bodies { circle { radius: 1 } position { x: 1.5 y: 0 } }\n"));
  EXPECT_EQ(error.field, "bodies[1].position");
  EXPECT_EQ(error.line, 3);
  EXPECT_EQ(error.column, 31);
  EXPECT_NE(error.message.find("bodies[1] overlaps bodies[0] by 0.5 m"), std::string::npos)
      << error.message;
  EXPECT_EQ(error.to_string().rfind("test.textproto:3:31: bodies[1].position: ", 0), 0u)
      << error.to_string();
}

TEST(Overlap, ACircleInABoxAndTwoBoxesAreRefused) {
  EXPECT_EQ(refused(scene_with("bodies { box { half_extents { x: 2 y: 1 } } }\n"
                               "bodies { circle { radius: 0.5 } position { x: 2.3 y: 0 } }\n"))
                .field,
            "bodies[1].position");
  const SceneError boxes = refused(
      scene_with("bodies { box { half_extents { x: 1 y: 1 } } position { x: 3 y: 0 } }\n"
                 "bodies { box { half_extents { x: 1 y: 1 } } position { x: 0 y: 0 } }\n"
                 "bodies { box { half_extents { x: 1 y: 1 } } position { x: 4.9 y: 1.9 } }\n"));
  EXPECT_EQ(boxes.field, "bodies[2].position");
  EXPECT_NE(boxes.message.find("overlaps bodies[0] by 0.1 m"), std::string::npos) << boxes.message;
}

TEST(Overlap, AStaticBodyOverlappingADynamicOneIsRefused) {
  EXPECT_EQ(refused(scene_with("bodies { is_static: true box { half_extents { x: 5 y: 1 } } }\n"
                               "bodies { circle { radius: 1 } position { x: 4 y: 1.5 } }\n"))
                .field,
            "bodies[1].position");
}

TEST(Overlap, AGridWhoseSpacingIsSmallerThanItsBodiesIsRefusedAtTheGrid) {
  const SceneError error =
      refused(scene_with("grids {\n"
                         "  body { circle { radius: 0.5 } }\n"
                         "  origin { x: -5 y: -5 }\n"
                         "  spacing { x: 0.9 y: 2 }\n"
                         "  count_x: 3 count_y: 1\n"
                         "}\n"));
  EXPECT_EQ(error.field, "grids[0]");
  EXPECT_EQ(error.line, 2);
  EXPECT_NE(error.message.find("grids[0] (its body 1) overlaps grids[0] (its body 0) by 0.1 m"),
            std::string::npos)
      << error.message;
}

TEST(Overlap, TouchingBodiesAndOverlappingStaticBodiesAreAccepted) {
  // A column of boxes edge to edge on a floor, circles side by side, a grid at exactly
  // its bodies' size, and two static pieces of level that overlap.
  const SceneDef def = accepted(scene_with(
      "bodies { is_static: true box { half_extents { x: 9 y: 0.5 } } position { x: 0 y: -9.5 } }\n"
      "bodies { is_static: true box { half_extents { x: 0.5 y: 5 } } position { x: -8.6 y: -5 } }\n"
      "bodies { box { half_extents { x: 0.5 y: 0.5 } } position { x: 0 y: -8.5 } }\n"
      "bodies { box { half_extents { x: 0.5 y: 0.5 } } position { x: 0 y: -7.5 } }\n"
      "bodies { circle { radius: 0.5 } position { x: 3 y: -8.5 } }\n"
      "bodies { circle { radius: 0.5 } position { x: 4 y: -8.5 } }\n"
      "grids { body { circle { radius: 0.1 } } origin { x: -5 y: 0 } spacing { x: 0.2 y: 0.2 }\n"
      "        count_x: 20 count_y: 20 }\n"));
  EXPECT_EQ(def.bodies.size(), 6u + 400u);
}

}  // namespace
}  // namespace scene
