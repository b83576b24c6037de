// The scene library (testing/scenes) builds exactly the scenes the tests, the bench
// and physics-settle relied on when each wrote its own: for every scene, its body
// count, a fingerprint of every field of every body definition in order, and the
// world's state hash after a few steps. The constants were taken from the scenes
// as the stability tests (pile_test.cpp, resting_test.cpp), physics-settle and the
// bench built them before they were written once here; a change to a constant means a
// scene changed, and with it every figure and bound measured on it.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/world.h"
#include "physics_test_support.h"
#include "scenes/scenes.h"

namespace phys::testing {
namespace {

// FNV-1a over the bits of every field of every body definition, in scene order.
std::uint64_t fingerprint(const scenes::SceneSpec& scene) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  const auto mix = [&h](std::uint64_t word) {
    for (int i = 0; i < 8; ++i) {
      h ^= (word >> (8 * i)) & 0xffU;
      h *= 0x100000001b3ULL;
    }
  };
  const auto mix_double = [&](double v) { mix(std::bit_cast<std::uint64_t>(v)); };
  for (const scenes::BodySpec& spec : scene.bodies) {
    const BodyDef b = scenes::to_body_def(spec);
    mix(static_cast<std::uint64_t>(b.shape));
    mix(static_cast<std::uint64_t>(b.motion));
    for (const double v : {b.position.x, b.position.y, b.velocity.x, b.velocity.y, b.acceleration.x,
                           b.acceleration.y, b.radius, b.half_extents.x, b.half_extents.y, b.mass,
                           b.restitution, b.friction.x, b.friction.y, b.contact_friction}) {
      mix_double(v);
    }
  }
  return h;
}

struct Expected {
  std::string label;
  scenes::SceneSpec scene;
  std::size_t bodies;
  std::uint64_t fingerprint;
  int steps;
  std::uint64_t hash_after_steps;
};

std::uint64_t hash_after(const scenes::SceneSpec& scene, int steps) {
  WorldSettings settings;
  settings.gravity = scene.gravity;
  World world(settings);
  scenes::add_to_world(world, scene);
  for (int i = 0; i < steps; ++i) world.step(kDt);
  return world.state_hash();
}

std::vector<Expected> build_expected_scenes() {
  using scenes::RainedCircles;
  using scenes::StageVariant;
  return {
      // The 16,000-circle pile: tests/stability/pile_test.cpp, the bench's pile-rain
      // scenes and physics-settle --width 100 --circles 16000 --per-row 80 all built
      // these bodies.
      {"circle_pile_16000_mu0_5", scenes::rained_circles_scene(scenes::circle_pile(16000, 0.5)),
       16003, 0xa04a86b25fcc3384, 30, 0x788fdac45fab985a},
      {"pile_rain_16000_mu0_5", scenes::pile_rain_scene(16000, 0.5, 1, 0, 0), 16003,
       0xa04a86b25fcc3384, 30, 0x788fdac45fab985a},
      {"circle_pile_16000_mu0", scenes::rained_circles_scene(scenes::circle_pile(16000, 0.0)),
       16003, 0x95d47156ac6a9b49, 30, 0x62db9144bc863c17},
      // The small and deep rained piles of tests/stability/resting_test.cpp, which
      // physics-settle builds without --per-row.
      {"rained_300_in_20m_mu0_5", scenes::rained_circles_scene(RainedCircles{20.0, 300, 0.5, 0}),
       303, 0x29641174fbab97c8, 120, 0xfaca04bde40de77c},
      {"rained_30_in_3_6m_mu0_5", scenes::rained_circles_scene(RainedCircles{3.6, 30, 0.5, 0}), 33,
       0x1943fca8f873569b, 120, 0x34ffa1f37dd3971d},
      {"rained_2000_in_20m_mu0", scenes::rained_circles_scene(RainedCircles{20.0, 2000, 0.0, 0}),
       2003, 0x874560e586850f80, 60, 0x257ef5c71f8815e8},
      // The bench's scenes (physics-bench, physics-contact-bench, physics-microbench).
      {"rain_16000", scenes::rain_scene(16000, 1, 0, 0), 16003, 0x97b25f2a09af8513, 30,
       0x8c30ee4029d2d5cb},
      {"rain_4000", scenes::rain_scene(4000, 1, 0, 0), 4003, 0x584850b3fd87bfb8, 60,
       0x5fb3821f2d2b2b88},
      {"pile_1000", scenes::pile_scene(1000), 1003, 0x41a2d287b8d67ed2, 60, 0x92f97f1b42582b3b},
      {"pyramid_5050", scenes::pyramid_scene(100, 1), 5051, 0xe90507ced1cc083e, 30,
       0xd115b2fce05f8c41},
      {"column_50", scenes::column_scene(50, false, 1), 51, 0x251304ee8ff324d0, 60,
       0x25ca936f01738a6e},
      {"column_mass_10", scenes::column_scene(10, true, 1), 11, 0x66a2122ac99776dc, 60,
       0x1739508283710a85},
      {"bounce_e0_5", scenes::bounce_scene(0.5, 1), 2, 0x6eedcbe5c3bed881, 60, 0x27379ded29fd80e8},
      {"projectile_friction", scenes::projectile_scene(0.8), 1, 0x9334fca87f3fa908, 60,
       0xf9902562b9196fd9},
      {"friction_dtk_0_1", scenes::friction_decay_scene(0.1), 1, 0x6987e89aa0616f70, 60,
       0x31f632a0d5a3f9be},
      {"stages_all", scenes::stages_scene(StageVariant::All, 1), 4004, 0x515ce890225d566f, 30,
       0x470427eb2b17551b},
      {"stages_no_gravity", scenes::stages_scene(StageVariant::NoGravity, 1), 4004,
       0x515ce890225d566f, 30, 0x35412dcf57c64f8c},
      {"stages_no_friction", scenes::stages_scene(StageVariant::NoFriction, 1), 4004,
       0x3db67c3c9a5cb0ef, 30, 0x8a09d2f4c4ef7ea9},
      {"stages_no_restitution", scenes::stages_scene(StageVariant::NoRestitution, 1), 4004,
       0x90c2776aebfbe7e7, 30, 0xf84f56f5d5284709},
      {"stages_circles_only", scenes::stages_scene(StageVariant::CirclesOnly, 1), 4004,
       0x93c8478e124a05d3, 30, 0x0cd53957e2f06cc4},
      {"stages_boxes_only", scenes::stages_scene(StageVariant::BoxesOnly, 1), 4004,
       0x9cef137dcebda963, 30, 0x1ba8ca4b7065e9b3},
  };
}

// Built once a process: the test names are made at start-up, in every process that
// runs any test of this binary, and the scenes hold some 100,000 bodies.
const std::vector<Expected>& expected_scenes() {
  static const std::vector<Expected> scenes = build_expected_scenes();
  return scenes;
}

class SceneLibrary : public ::testing::TestWithParam<std::size_t> {};

TEST_P(SceneLibrary, BuildsTheBodiesTheTestsAndBenchReliedOn) {
  const Expected& e = expected_scenes()[GetParam()];
  EXPECT_EQ(e.scene.bodies.size(), e.bodies);
  EXPECT_EQ(fingerprint(e.scene), e.fingerprint)
      << "fingerprint 0x" << std::hex << fingerprint(e.scene);
  const std::uint64_t hash = hash_after(e.scene, e.steps);
  EXPECT_EQ(hash, e.hash_after_steps) << "state hash 0x" << std::hex << hash;
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneLibrary,
                         ::testing::Range<std::size_t>(0, expected_scenes().size()),
                         [](const auto& param_info) {
                           return expected_scenes()[param_info.param].label;
                         });

// The broadphase benchmark's boxes, folded into one number as they were captured.
TEST(SceneLibrary, RandomBoxesAreTheBenchmarksBoxes) {
  std::uint64_t h = 0;
  for (const Aabb& box : scenes::random_boxes(1000, 0.3, 42)) {
    h = h * 31 + std::bit_cast<std::uint64_t>(box.min.x) + std::bit_cast<std::uint64_t>(box.max.y);
  }
  EXPECT_EQ(h, 0x10660c2a90fc166cULL) << std::hex << h;
}

// A rained pile's container holds its circles: the walls' inner faces are at
// +-width/2, the floor's top at 0, and every circle starts inside.
TEST(SceneLibrary, RainedCirclesStartInsideTheirContainer) {
  for (const int per_row : {0, 80}) {
    const scenes::SceneSpec scene = scenes::rained_circles_scene({100.0, 1000, 0.5, per_row});
    EXPECT_EQ(scenes::dynamic_count(scene), 1000u);
    for (const scenes::BodySpec& body : scene.bodies) {
      if (body.is_static) continue;
      EXPECT_GT(body.position.x - body.radius, scene.container.min.x);
      EXPECT_LT(body.position.x + body.radius, scene.container.max.x);
      EXPECT_GT(body.position.y - body.radius, scene.container.min.y);
    }
  }
}

// A body the world refuses is a clear error naming the scene, the body and why, not a
// world silently missing a body.
TEST(SceneLibrary, ARefusedBodyThrowsWithTheSceneTheBodyAndTheReason) {
  scenes::SceneSpec scene = scenes::bounce_scene(0.5, 1);
  scene.bodies[1].radius = -1.0;
  World world;
  try {
    scenes::add_to_world(world, scene);
    FAIL() << "a body of radius -1 was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()),
              "scene bounce-e0.5: body 1 refused: radius must be a finite number > 0");
  }
}

// add_to_world returns the ids in the scene's order, and the world holds those bodies.
TEST(SceneLibrary, AddToWorldReturnsTheIdsInSceneOrder) {
  const scenes::SceneSpec scene = scenes::column_scene(5, false, 1);
  World world;
  const std::vector<BodyId> ids = scenes::add_to_world(world, scene);
  ASSERT_EQ(ids.size(), scene.bodies.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto body = world.body(ids[i]);
    ASSERT_TRUE(body.has_value());
    EXPECT_EQ(body->position, scene.bodies[i].position) << "body " << i;
  }
}

}  // namespace
}  // namespace phys::testing
