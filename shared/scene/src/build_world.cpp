#include <stdexcept>
#include <string>

#include "scene/scene.h"

namespace scene {

phys::World build_world(const SceneDef& scene) {
  if (phys::check_settings(scene.world) != phys::SettingsError::None)
    throw std::invalid_argument(std::string("scene world settings refused: ") +
                                phys::describe(phys::check_settings(scene.world)));
  phys::World world(scene.world);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    phys::BodyDefError error = phys::BodyDefError::None;
    if (!world.add_body(scene.bodies[i], &error).is_valid())
      throw std::invalid_argument("scene body " + std::to_string(i) +
                                  " refused by the world: " + std::string(phys::describe(error)));
  }
  return world;
}

double fixed_dt(const SceneDef& scene) { return 1.0 / scene.tick_rate; }

}  // namespace scene
