#include "golden_worlds.h"

#include "physics/det_math.h"
#include "physics/fnv_hash.h"
#include "physics/world.h"
#include "scenes/determinism_scene.h"
#include "scenes/scenes.h"

namespace portable {
namespace {

constexpr double kDt = 1.0 / 60.0;

// As scene_library_test.cpp's hash_after: default settings, the scene's gravity.
GoldenWorld library_scene(std::string name, scenes::SceneSpec scene, int steps) {
  return {std::move(name), [scene = std::move(scene), steps] {
            phys::WorldSettings settings;
            settings.gravity = scene.gravity;
            phys::World world(settings);
            scenes::add_to_world(world, scene);
            for (int i = 0; i < steps; ++i) world.step(kDt);
            return world.state_hash();
          }};
}

std::uint64_t determinism_scene() {
  phys::World world;
  const std::vector<phys::BodyId> ids = scenes::add_determinism_scene(world);
  for (int step = 0; step < scenes::kDeterminismSteps; ++step) {
    scenes::apply_determinism_inputs(world, ids, step);
    world.step(kDt);
  }
  return world.state_hash();
}

// Every result of det::exp, expm1 and log on 100,000 points of the ranges the core
// uses, hashed: equal on two platforms means the functions round alike there.
std::uint64_t det_math_results() {
  phys::Fnv1a64 hash;
  for (int i = 0; i < 100000; ++i) {
    const double u = (i + 0.5) / 100000.0;
    hash.mix_double(phys::det::exp(-50.0 * u));
    hash.mix_double(phys::det::expm1(-0.5 * u));
    hash.mix_double(phys::det::expm1(-40.0 * u));
    hash.mix_double(phys::det::log(u));
  }
  return hash.value();
}

}  // namespace

std::vector<GoldenWorld> golden_worlds() {
  using scenes::RainedCircles;
  using scenes::StageVariant;
  // The library's golden table without its three 16,000-circle piles (the same
  // code as rained_300 and rain_4000, at four times the cost under emulation).
  return {
      {"det_math_results", det_math_results},
      {"determinism_scene_1000", determinism_scene},
      library_scene("rained_300_in_20m_mu0_5",
                    scenes::rained_circles_scene(RainedCircles{20.0, 300, 0.5, 0}), 120),
      library_scene("rained_30_in_3_6m_mu0_5",
                    scenes::rained_circles_scene(RainedCircles{3.6, 30, 0.5, 0}), 120),
      library_scene("rained_2000_in_20m_mu0",
                    scenes::rained_circles_scene(RainedCircles{20.0, 2000, 0.0, 0}), 60),
      library_scene("rain_4000", scenes::rain_scene(4000, 1, 0, 0), 60),
      library_scene("pile_1000", scenes::pile_scene(1000), 60),
      library_scene("pyramid_5050", scenes::pyramid_scene(100, 1), 30),
      library_scene("column_50", scenes::column_scene(50, false, 1), 60),
      library_scene("column_mass_10", scenes::column_scene(10, true, 1), 60),
      library_scene("bounce_e0_5", scenes::bounce_scene(0.5, 1), 60),
      library_scene("projectile_friction", scenes::projectile_scene(0.8), 60),
      library_scene("friction_dtk_0_1", scenes::friction_decay_scene(0.1), 60),
      library_scene("stages_all", scenes::stages_scene(StageVariant::All, 1), 30),
      library_scene("stages_no_gravity", scenes::stages_scene(StageVariant::NoGravity, 1), 30),
      library_scene("stages_no_friction", scenes::stages_scene(StageVariant::NoFriction, 1), 30),
      library_scene("stages_no_restitution", scenes::stages_scene(StageVariant::NoRestitution, 1),
                    30),
      library_scene("stages_circles_only", scenes::stages_scene(StageVariant::CirclesOnly, 1), 30),
      library_scene("stages_boxes_only", scenes::stages_scene(StageVariant::BoxesOnly, 1), 30),
  };
}

}  // namespace portable
