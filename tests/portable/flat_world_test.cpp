// The flat world format: a scene file flattened, written as JSON, read back and
// built runs exactly as the scene itself (the same state hash after 120 steps),
// and numbers that do not describe a world are refused, each with its reason.
#include "portable/flat_world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "scene/scene.h"

namespace portable {
namespace {

constexpr int kSteps = 120;

scene::SceneDef load(const std::filesystem::path& path) {
  scene::SceneResult loaded = scene::load_scene_file(path);
  if (const auto* error = std::get_if<scene::SceneError>(&loaded))
    ADD_FAILURE() << error->to_string();
  return std::get<scene::SceneDef>(std::move(loaded));
}

std::vector<double> flat_of(const scene::SceneDef& def) {
  return flatten({def.world, scene::fixed_dt(def), def.bodies});
}

template <typename T>
T value_or_fail(std::variant<T, std::string> result) {
  if (const auto* error = std::get_if<std::string>(&result)) {
    ADD_FAILURE() << *error;
    return T{};
  }
  return std::get<T>(std::move(result));
}

// The reason unflatten gives; "" when it accepted the numbers.
std::string refusal(const std::vector<double>& values) {
  const auto result = unflatten(values);
  const auto* error = std::get_if<std::string>(&result);
  return error ? *error : "";
}

TEST(FlatWorld, EverySceneFileRunsAsItselfAfterAJsonRoundTrip) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(PHYSICS_SCENES_DIR)) {
    if (entry.path().extension() != ".textproto") continue;
    ++scenes;
    const scene::SceneDef def = load(entry.path());
    const std::vector<double> values = value_or_fail(from_json(to_json(flat_of(def))));
    const FlatWorld flat = value_or_fail(unflatten(values));
    EXPECT_EQ(flat.dt, scene::fixed_dt(def));
    auto built = build_world(flat);
    ASSERT_TRUE(std::holds_alternative<phys::World>(built)) << std::get<std::string>(built);
    phys::World& ours = std::get<phys::World>(built);
    phys::World reference = scene::build_world(def);
    ASSERT_EQ(ours.state_hash(), reference.state_hash()) << entry.path();
    for (int i = 0; i < kSteps; ++i) {
      ours.step(flat.dt);
      reference.step(scene::fixed_dt(def));
    }
    EXPECT_EQ(ours.state_hash(), reference.state_hash()) << entry.path();
  }
  EXPECT_GE(scenes, 6);
}

TEST(FlatWorld, OnlyAWorldWithFiltersSensorsOrKinematicBodiesIsVersion2) {
  const std::filesystem::path dir = PHYSICS_SCENES_DIR;
  EXPECT_EQ(flat_of(load(dir / "platformer.textproto"))[0], kFlatVersion);
  const std::vector<double> rules = flat_of(load(dir / "rules-room.textproto"));
  EXPECT_EQ(rules[0], kFlatVersionWithFilters);
  const FlatWorld flat = value_or_fail(unflatten(rules));
  const scene::SceneDef def = load(dir / "rules-room.textproto");
  ASSERT_EQ(flat.bodies.size(), def.bodies.size());
  for (std::size_t i = 0; i < def.bodies.size(); ++i) {
    EXPECT_EQ(flat.bodies[i].motion, def.bodies[i].motion) << i;
    EXPECT_EQ(flat.bodies[i].filter, def.bodies[i].filter) << i;
    EXPECT_EQ(flat.bodies[i].is_sensor, def.bodies[i].is_sensor) << i;
  }
  // A version 2 body's fields are checked as the others are.
  std::vector<double> bad = rules;
  bad[kFlatHeader + kFlatBodyFields + 2] = 3e9;  // the first body's group
  const auto refused = unflatten(bad);
  ASSERT_TRUE(std::holds_alternative<std::string>(refused));
  EXPECT_NE(std::get<std::string>(refused).find("version 2: body 0: value"), std::string::npos)
      << std::get<std::string>(refused);
}

TEST(FlatWorld, NumbersKeepEveryBitThroughJson) {
  const std::vector<double> values = {1.0 / 3.0, -0.0, 5e-324, 1.7976931348623157e308, -9.81, 0.1};
  const std::vector<double> back = value_or_fail(from_json(to_json(values)));
  ASSERT_EQ(back.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(back[i], values[i]) << i;
    EXPECT_EQ(std::signbit(back[i]), std::signbit(values[i])) << i;
  }
}

TEST(FlatWorld, BadJsonIsRefusedSayingWhere) {
  const auto error = [](std::string_view text) {
    const auto result = from_json(text);
    const auto* message = std::get_if<std::string>(&result);
    return message ? *message : std::string();
  };
  EXPECT_NE(error("").find("expected '['"), std::string::npos);
  EXPECT_NE(error("[1, 2").find("expected ',' or ']'"), std::string::npos);
  EXPECT_NE(error("[1, nan]").find("byte 4: expected a finite number"), std::string::npos);
  EXPECT_NE(error("[1e999]").find("expected a finite number"), std::string::npos);
  EXPECT_NE(error("[1,]").find("expected a finite number"), std::string::npos);
  EXPECT_NE(error("[1] 2").find("text after the array"), std::string::npos);
  EXPECT_EQ(error(" [ ] "), "");
}

class BadFlatWorld : public ::testing::Test {
 protected:
  // Default settings, dt 1/60, one dynamic circle.
  std::vector<double> good() const {
    FlatWorld world;
    phys::BodyDef circle;
    circle.shape = phys::Shape::Circle;
    world.bodies.push_back(circle);
    return flatten(world);
  }
};

TEST_F(BadFlatWorld, TheGoodOneIsAccepted) { EXPECT_EQ(refusal(good()), ""); }

TEST_F(BadFlatWorld, WrongVersionOrLength) {
  EXPECT_NE(refusal({}).find("version"), std::string::npos);
  std::vector<double> v = good();
  v[0] = 2.0;
  EXPECT_NE(refusal(v).find("version"), std::string::npos);
  EXPECT_NE(refusal({1.0, 0.0}).find("at least 28 values"), std::string::npos);
  v = good();
  v.pop_back();
  EXPECT_NE(refusal(v).find("1 bodies take 44 values, got 43"), std::string::npos);
  v = good();
  v[kFlatHeader - 1] = 1e9;  // a body count beyond the core's limit, never allocated
  EXPECT_NE(refusal(v).find("body count"), std::string::npos);
}

TEST_F(BadFlatWorld, WholeNumbersAndFlags) {
  std::vector<double> v = good();
  v[3] = 3.0;  // integrator
  EXPECT_NE(refusal(v).find("(integrator) must be a whole number in [0, 2]"), std::string::npos);
  v = good();
  v[4] = 1.5;  // substeps
  EXPECT_NE(refusal(v).find("substeps"), std::string::npos);
  v = good();
  v[9] = 2.0;  // continuous
  EXPECT_NE(refusal(v).find("continuous"), std::string::npos);
  v = good();
  v[kFlatHeader] = 0.5;  // the body's shape
  EXPECT_NE(refusal(v).find("body 0: value"), std::string::npos);
}

TEST_F(BadFlatWorld, SettingsAndDtTheCoreRefuses) {
  std::vector<double> v = good();
  v[5] = -1.0;  // slop
  EXPECT_NE(refusal(v).find("settings refused"), std::string::npos);
  v = good();
  v[kFlatHeader - 2] = 0.0;  // dt
  EXPECT_NE(refusal(v).find("dt must be"), std::string::npos);
}

TEST_F(BadFlatWorld, ABodyTheCoreRefusesIsNamed) {
  std::vector<double> v = good();
  v[kFlatHeader + 8] = -1.0;  // radius
  const FlatWorld flat = value_or_fail(unflatten(v));
  const auto built = build_world(flat);
  ASSERT_TRUE(std::holds_alternative<std::string>(built));
  EXPECT_NE(std::get<std::string>(built).find("body 0 refused by the world"), std::string::npos);
}

}  // namespace
}  // namespace portable
