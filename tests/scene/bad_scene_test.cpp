// Every kind of bad scene is refused with an error that names the field at fault
// and, where the text says where, the line. Nothing crashes on any input.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::accepted;
using testing::refused;

// A valid scene; each test appends or replaces one thing. Line numbers below
// count from the first line of the test's own text.
constexpr std::string_view kWorld =
    "world { bounds { min { x: -10 y: -10 } max { x: 10 y: 10 } } }\n";
constexpr std::string_view kSpawn = "spawn_points { x: 1 y: 1 }\n";

std::string scene_with(std::string_view bodies) {
  return std::string(kWorld) + std::string(bodies) + std::string(kSpawn);
}

TEST(BadScene, BaseSceneIsAccepted) {
  const SceneDef def = accepted(scene_with("bodies { circle { radius: 0.5 } }\n"));
  EXPECT_EQ(def.bodies.size(), 1u);
}

TEST(BadScene, UnknownFieldNamesTheFieldAndLine) {
  const SceneError error =
      refused(scene_with("bodies {\n"
                         "  circle { radius: 0.5 }\n"
                         "  radiuss: 1\n"
                         "}\n"));
  EXPECT_EQ(error.file, "test.textproto");
  EXPECT_EQ(error.line, 4);
  EXPECT_EQ(error.column, 10) << "Protobuf points just after the unknown name";
  EXPECT_EQ(error.field, "radiuss");
  EXPECT_NE(error.message.find("no field named"), std::string::npos) << error.message;
  EXPECT_EQ(error.to_string().rfind("test.textproto:4:10: radiuss: ", 0), 0u) << error.to_string();
}

TEST(BadScene, SyntaxErrorGivesTheLine) {
  const SceneError error = refused(scene_with("bodies { circle { radius: 0.5 }\n"));
  EXPECT_GT(error.line, 0);
  const SceneError missing_value = refused("name: \"x\"\nworld { tick_rate: }\n");
  EXPECT_EQ(missing_value.line, 2);
}

TEST(BadScene, UnknownEnumValueAndRepeatedSingularFieldAreParseErrors) {
  // Protobuf reports a parse error at the token after the bad one: on the same line here.
  const SceneError enum_error =
      refused("name: \"a\"\nworld { integrator: RUNGE_KUTTA }\n" + std::string(kSpawn));
  EXPECT_EQ(enum_error.line, 2);
  EXPECT_NE(enum_error.message.find("RUNGE_KUTTA"), std::string::npos) << enum_error.message;
  const SceneError twice = refused("name: \"a\"\nname: \"b\"\n" + std::string(kSpawn));
  EXPECT_EQ(twice.line, 2);
}

TEST(BadScene, NamesMustBeShortValidUtf8) {
  // Names go to clients in proto3 strings, which a peer refuses unless valid UTF-8.
  EXPECT_EQ(refused("name: \"bad\\xff\"\n" + std::string(kSpawn)).field, "name");
  EXPECT_EQ(refused(scene_with("bodies { name: \"\\xc3\" circle { radius: 1 } }\n")).field,
            "bodies[0].name");
  EXPECT_EQ(refused("name: \"" + std::string(300, 'a') + "\"\n" + std::string(kSpawn)).field,
            "name");
  EXPECT_EQ(accepted("name: \"caf\xc3\xa9 \xe2\x9c\x93\"\n" + std::string(kSpawn)).name,
            "caf\xc3\xa9 \xe2\x9c\x93");
}

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

TEST(BadScene, TwoShapesInOneBodyAreRefusedByTheParser) {
  const SceneError error = refused(
      scene_with("bodies {\n circle { radius: 1 }\n box { half_extents { x: 1 y: 1 } }\n}\n"));
  EXPECT_EQ(error.line, 4);
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

class SceneFile : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& name, const std::string& bytes) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("scene_tests_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

SceneError load_error(const std::filesystem::path& path) {
  SceneResult result = load_scene_file(path);
  if (const auto* error = std::get_if<SceneError>(&result)) return *error;
  ADD_FAILURE() << path << " was accepted";
  return {};
}

TEST_F(SceneFile, MissingFileIsRefused) {
  const SceneError error = load_error(dir_ / "missing.textproto");
  EXPECT_EQ(error.file, (dir_ / "missing.textproto").string());
  EXPECT_NE(error.message.find("cannot open"), std::string::npos) << error.message;
}

TEST_F(SceneFile, DirectoryIsRefused) {
  EXPECT_NE(load_error(dir_).message.find("not a regular file"), std::string::npos);
}

TEST_F(SceneFile, EmptyFileIsRefused) {
  const SceneError error = load_error(write("empty.textproto", ""));
  EXPECT_NE(error.message.find("empty"), std::string::npos) << error.message;
}

TEST_F(SceneFile, GarbageBytesAreRefusedWithALine) {
  std::string bytes = "\x89PNG\r\n\x1a\n";
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
  const SceneError error = load_error(write("garbage.textproto", bytes));
  EXPECT_EQ(error.file, (dir_ / "garbage.textproto").string());
  EXPECT_GT(error.line, 0);
  EXPECT_FALSE(error.message.empty());
}

TEST_F(SceneFile, FileLargerThanTheLimitIsRefusedBeforeReading) {
  const auto path = dir_ / "big.textproto";
  std::filesystem::resize_file(write("big.textproto", ""), kMaxSceneFileBytes + 1);
  EXPECT_NE(load_error(path).message.find("limit"), std::string::npos);
}

TEST_F(SceneFile, ErrorsNameTheFile) {
  const auto path = write("bad.textproto", scene_with("bodies { circle { radius: -1 } }\n"));
  const SceneError error = load_error(path);
  EXPECT_EQ(error.to_string(),
            path.string() + ":2:19: bodies[0].circle.radius: must be > 0, got -1");
}

// Random bytes, and the default scene with random bytes changed, never crash
// the loader: each is either accepted or refused with a message.
TEST(BadScene, RandomInputNeverCrashes) {
  std::mt19937 random(12345);
  const std::string base(default_scene_text());
  for (int round = 0; round < 2000; ++round) {
    std::string text;
    if (round % 2 == 0) {
      text.resize(random() % 400);
      for (char& c : text) c = static_cast<char>(random() % 256);
    } else {
      text = base;
      for (int edits = 0; edits < 4; ++edits) {
        const std::size_t at = random() % text.size();
        text[at] = "{}:-.0123456789e \nxnaif"[random() % 23];
      }
    }
    SceneResult result = parse_scene_text(text, "random");
    if (const auto* error = std::get_if<SceneError>(&result)) {
      EXPECT_FALSE(error->message.empty());
    }
  }
}

}  // namespace
}  // namespace scene
