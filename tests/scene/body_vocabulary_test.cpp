// The scene format's physics vocabulary: filters, sensors, kinematic bodies and
// names are carried into the BodyDef; a filter wider than 32 bits, a kinematic body
// with a mass or an acceleration, a body both static and kinematic, and a kinematic
// player are refused, naming the body's field; pairs that never collide may start
// inside each other.
#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::accepted;
using testing::refused;
using testing::scene_with;

TEST(SceneVocabulary, FiltersSensorsKinematicAndNamesAreCarried) {
  const SceneDef def = accepted(
      scene_with("bodies { name: \"goal\" box { half_extents { x: 1 y: 1 } } is_static: true "
                 "is_sensor: true }\n"
                 "bodies { name: \"lift\" box { half_extents { x: 1 y: 0.2 } } is_kinematic: true\n"
                 "         position { x: 4 } velocity { x: 1 } }\n"
                 "bodies { circle { radius: 0.5 } position { y: 5 }\n"
                 "         category_bits: 4 mask_bits: 0xfffffffe group: -3 }\n"));
  ASSERT_EQ(def.bodies.size(), 3u);
  EXPECT_EQ(def.bodies[0].name, "goal");
  EXPECT_TRUE(def.bodies[0].is_sensor);
  EXPECT_EQ(def.bodies[0].motion, phys::Motion::Static);
  EXPECT_EQ(def.bodies[1].name, "lift");
  EXPECT_EQ(def.bodies[1].motion, phys::Motion::Kinematic);
  EXPECT_EQ(def.bodies[1].velocity, (phys::Vec2{1.0, 0.0}));
  EXPECT_FALSE(def.bodies[1].is_sensor);
  EXPECT_EQ(def.bodies[1].filter, phys::Filter{});  // the defaults: everything collides
  EXPECT_EQ(def.bodies[2].filter.category_bits, 4u);
  EXPECT_EQ(def.bodies[2].filter.mask_bits, 0xfffffffeu);
  EXPECT_EQ(def.bodies[2].filter.group, -3);
  const phys::World world = build_world(def);
  EXPECT_EQ(world.find_body("lift"), (phys::BodyId{1, 1}));
  EXPECT_TRUE(world.is_sensor(phys::BodyId{0, 1}));
}

TEST(SceneVocabulary, FilterBitsBeyond32AreRefusedNamingTheBody) {
  const SceneError error =
      refused(scene_with("bodies { circle { radius: 0.5 } }\n"
                         "bodies { name: \"ghost\" circle { radius: 0.5 } position { x: 3 }\n"
                         "         category_bits: 0x100000000 }\n"));
  EXPECT_EQ(error.field, "bodies[1].category_bits");
  EXPECT_EQ(error.line, 4);
  EXPECT_NE(error.message.find("32 bits"), std::string::npos) << error.message;
  EXPECT_EQ(refused(scene_with("bodies { circle { radius: 0.5 } mask_bits: 0x1ffffffff }\n")).field,
            "bodies[0].mask_bits");
}

TEST(SceneVocabulary, AKinematicBodyWithMassOrAccelerationIsRefused) {
  SceneError error =
      refused(scene_with("bodies { circle { radius: 1 } is_kinematic: true mass: 2 }\n"));
  EXPECT_EQ(error.field, "bodies[0].mass");
  EXPECT_NE(error.message.find("kinematic"), std::string::npos) << error.message;
  error = refused(
      scene_with("bodies { circle { radius: 1 } is_kinematic: true acceleration { x: 1 } }\n"));
  EXPECT_EQ(error.field, "bodies[0].acceleration");
}

TEST(SceneVocabulary, StaticAndKinematicAtOnceIsRefused) {
  const SceneError error =
      refused(scene_with("bodies { circle { radius: 1 } is_static: true is_kinematic: true }\n"));
  EXPECT_EQ(error.field, "bodies[0].is_kinematic");
}

TEST(SceneVocabulary, AKinematicPlayerIsRefused) {
  const SceneError error =
      refused(scene_with("player { circle { radius: 0.5 } is_kinematic: true }\n"));
  EXPECT_EQ(error.field, "player.is_kinematic");
}

TEST(SceneVocabulary, PairsThatNeverCollideMayStartInsideEachOther) {
  // A sensor over a dynamic body, two kinematic bodies, a kinematic in a static one,
  // a negative group, masks that leave each other out.
  accepted(scene_with(
      "bodies { box { half_extents { x: 1 y: 1 } } is_static: true is_sensor: true }\n"
      "bodies { circle { radius: 0.5 } }\n"
      "bodies { box { half_extents { x: 1 y: 1 } } position { x: 5 } is_kinematic: true }\n"
      "bodies { box { half_extents { x: 1 y: 1 } } position { x: 5 } is_kinematic: true }\n"
      "bodies { box { half_extents { x: 1 y: 1 } } position { x: 5 } is_static: true }\n"
      "bodies { circle { radius: 0.5 } position { y: 5 } group: -1 }\n"
      "bodies { circle { radius: 0.5 } position { y: 5.2 } group: -1 }\n"
      "bodies { circle { radius: 0.5 } position { x: -5 } category_bits: 2 mask_bits: 1 }\n"
      "bodies { circle { radius: 0.5 } position { x: -5.2 } category_bits: 2 mask_bits: 1 }\n"));
  // A kinematic body inside a dynamic one is still refused.
  const SceneError error =
      refused(scene_with("bodies { box { half_extents { x: 1 y: 1 } } is_kinematic: true }\n"
                         "bodies { circle { radius: 0.5 } }\n"));
  EXPECT_EQ(error.field, "bodies[1].position");
}

}  // namespace
}  // namespace scene
