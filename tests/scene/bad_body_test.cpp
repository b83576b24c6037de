// A body with a bad number (missing or non-positive size, no shape, bad mass, NaN,
// infinity, huge values, restitution or friction out of range, a static body that
// moves, a body outside the bounds) is refused, naming the body's field and line.
#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::accepted;
using testing::kSpawn;
using testing::kWorld;
using testing::refused;
using testing::scene_with;

TEST(BadScene, NegativeRadiusNamesTheBodyAndLine) {
  const SceneError error =
      refused(scene_with("bodies { circle { radius: 0.5 } }\n"
                         "bodies {\n"
                         "  circle { radius: -1 }\n"
                         "}\n"));
  EXPECT_EQ(error.field, "bodies[1].circle.radius");
  EXPECT_EQ(error.line, 4);
  EXPECT_NE(error.message.find("> 0"), std::string::npos) << error.message;
}

TEST(BadScene, MissingRadiusPointsAtTheCircle) {
  const SceneError error = refused(scene_with("bodies { circle { } }\n"));
  EXPECT_EQ(error.field, "bodies[0].circle.radius");
  EXPECT_EQ(error.line, 2) << "located at the nearest field that was written";
}

TEST(BadScene, ZeroHalfExtentIsRefused) {
  const SceneError error = refused(scene_with("bodies { box { half_extents { x: 1 y: 0 } } }\n"));
  EXPECT_EQ(error.field, "bodies[0].box.half_extents.y");
  EXPECT_EQ(refused(scene_with("bodies { box { } }\n")).field, "bodies[0].box.half_extents.x");
}

TEST(BadScene, BodyWithoutShapeIsRefused) {
  const SceneError error = refused(scene_with("bodies { position { x: 1 } }\n"));
  EXPECT_EQ(error.field, "bodies[0]");
  EXPECT_NE(error.message.find("no shape"), std::string::npos);
}

TEST(BadScene, NonPositiveMassOnDynamicBodyIsRefused) {
  for (const char* mass : {"0", "-2"}) {
    SCOPED_TRACE(mass);
    const SceneError error =
        refused(scene_with(std::string("bodies { circle { radius: 1 } mass: ") + mass + " }\n"));
    EXPECT_EQ(error.field, "bodies[0].mass");
    EXPECT_EQ(error.line, 2);
  }
}

TEST(BadScene, MassOnStaticBodyIsRefused) {
  const SceneError error =
      refused(scene_with("bodies { circle { radius: 1 } is_static: true mass: 3 }\n"));
  EXPECT_EQ(error.field, "bodies[0].mass");
}

TEST(BadScene, UnsetMassOnDynamicBodyDefaultsToOne) {
  const SceneDef def = accepted(scene_with("bodies { circle { radius: 1 } }\n"));
  ASSERT_EQ(def.bodies.size(), 1u);
  EXPECT_EQ(def.bodies[0].mass, 1.0);
}

TEST(BadScene, NaNIsRefusedWherever) {
  struct Case {
    const char* body;
    const char* field;
  };
  for (const Case& c : {
           Case{"circle { radius: nan }", "bodies[0].circle.radius"},
           Case{"circle { radius: 1 } position { x: nan }", "bodies[0].position.x"},
           Case{"circle { radius: 1 } velocity { y: nan }", "bodies[0].velocity.y"},
           Case{"circle { radius: 1 } acceleration { x: nan }", "bodies[0].acceleration.x"},
           Case{"circle { radius: 1 } mass: nan", "bodies[0].mass"},
           Case{"circle { radius: 1 } restitution: nan", "bodies[0].restitution"},
           Case{"circle { radius: 1 } friction { x: nan }", "bodies[0].friction.x"},
       }) {
    SCOPED_TRACE(c.body);
    EXPECT_EQ(refused(scene_with(std::string("bodies { ") + c.body + " }\n")).field, c.field);
  }
  EXPECT_EQ(refused("world { gravity { y: nan } }\n" + std::string(kSpawn)).field,
            "world.gravity.y");
  EXPECT_EQ(refused(std::string(kWorld) + "spawn_points { x: nan }\n").field, "spawn_points[0].x");
}

TEST(BadScene, InfinityIsRefused) {
  EXPECT_EQ(refused(scene_with("bodies { box { half_extents { x: inf y: 1 } } }\n")).field,
            "bodies[0].box.half_extents.x");
  EXPECT_EQ(refused(scene_with("bodies { circle { radius: 1 } velocity { x: -inf } }\n")).field,
            "bodies[0].velocity.x");
  EXPECT_EQ(refused("world { tick_rate: inf }\n" + std::string(kSpawn)).field, "world.tick_rate");
  EXPECT_EQ(
      refused("world { bounds { min { x: -inf } max { x: 1 y: 1 } } }\n" + std::string(kSpawn))
          .field,
      "world.bounds.min.x");
}

TEST(BadScene, HugeNumbersAreRefused) {
  EXPECT_EQ(refused(scene_with("bodies { circle { radius: 1e300 } }\n")).field,
            "bodies[0].circle.radius");
  // No bounds here: the coordinate limit applies alone.
  EXPECT_EQ(
      refused("bodies { circle { radius: 1 } position { x: 1e12 } }\n" + std::string(kSpawn)).field,
      "bodies[0].position.x");
  EXPECT_EQ(refused(scene_with("bodies { circle { radius: 1 } velocity { x: 1e9 } }\n")).field,
            "bodies[0].velocity");
  // An integer too large for its field is a parse error, with its line.
  const SceneError error = refused("world {\n steps_per_frame: 99999999999999999999999\n}\n");
  EXPECT_EQ(error.line, 2);
}

TEST(BadScene, RestitutionOutsideZeroToOneIsRefused) {
  for (const char* value : {"-0.1", "1.5"}) {
    EXPECT_EQ(refused(scene_with(std::string("bodies { circle { radius: 1 } restitution: ") +
                                 value + " }\n"))
                  .field,
              "bodies[0].restitution");
  }
}

TEST(BadScene, NegativeFrictionIsRefused) {
  EXPECT_EQ(refused(scene_with("bodies { circle { radius: 1 } friction { y: -1 } }\n")).field,
            "bodies[0].friction.y");
}

TEST(BadScene, ContactFrictionIsCarriedIntoTheBody) {
  const SceneDef def =
      accepted(scene_with("bodies { circle { radius: 1 } contact_friction: 0.3 }\n"));
  ASSERT_EQ(def.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(def.bodies[0].contact_friction, 0.3);
}

TEST(BadScene, NegativeContactFrictionIsRefused) {
  EXPECT_EQ(refused(scene_with("bodies { circle { radius: 1 } contact_friction: -0.5 }\n")).field,
            "bodies[0].contact_friction");
}

TEST(BadScene, StaticBodyThatMovesIsRefused) {
  EXPECT_EQ(
      refused(scene_with("bodies { circle { radius: 1 } is_static: true velocity { x: 1 } }\n"))
          .field,
      "bodies[0].velocity");
  EXPECT_EQ(
      refused(scene_with("bodies { circle { radius: 1 } is_static: true acceleration { y: 1 } }\n"))
          .field,
      "bodies[0].acceleration");
}

TEST(BadScene, BodyOutOfBoundsIsRefused) {
  const SceneError error =
      refused(scene_with("bodies { circle { radius: 1 } position { x: 0 y: 0 } }\n"
                         "bodies { circle { radius: 0.5 } position { x: 9.8 y: 0 } }\n"));
  EXPECT_EQ(error.field, "bodies[1].position");
  EXPECT_EQ(error.line, 3);
  EXPECT_NE(error.message.find("outside world.bounds"), std::string::npos) << error.message;
  // Touching the bounds from inside is fine.
  accepted(scene_with("bodies { circle { radius: 0.5 } position { x: 9.5 y: -9.5 } }\n"));
}

}  // namespace
}  // namespace scene
