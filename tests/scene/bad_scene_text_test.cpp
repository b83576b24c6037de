// Text that does not parse as a scene (unknown fields, syntax errors, bad enum values,
// fields given twice, names that are not short valid UTF-8) is refused with the field
// and the line; random bytes never crash the loader.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::accepted;
using testing::kSpawn;
using testing::refused;
using testing::scene_with;

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

TEST(BadScene, TwoShapesInOneBodyAreRefusedByTheParser) {
  const SceneError error = refused(
      scene_with("bodies {\n circle { radius: 1 }\n box { half_extents { x: 1 y: 1 } }\n}\n"));
  EXPECT_EQ(error.line, 4);
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
