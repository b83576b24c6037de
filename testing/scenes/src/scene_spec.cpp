#include "scenes/scene_spec.h"

#include <stdexcept>
#include <string>

#include "physics/world.h"

namespace scenes {

std::size_t dynamic_count(const SceneSpec& scene) {
  std::size_t count = 0;
  for (const BodySpec& body : scene.bodies) {
    if (!body.is_static) ++count;
  }
  return count;
}

phys::BodyDef to_body_def(const BodySpec& spec) {
  phys::BodyDef def;
  def.shape = spec.shape;
  def.motion = spec.is_static ? phys::Motion::Static : phys::Motion::Dynamic;
  def.position = spec.position;
  def.velocity = spec.velocity;
  def.acceleration = spec.acceleration;
  def.radius = spec.radius;
  def.half_extents = spec.half_extents;
  def.mass = spec.mass;
  def.restitution = spec.restitution;
  def.friction = spec.friction;
  def.contact_friction = spec.contact_friction;
  return def;
}

std::vector<phys::BodyId> add_to_world(phys::World& world, const SceneSpec& scene) {
  std::vector<phys::BodyId> ids;
  ids.reserve(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    phys::BodyDefError error = phys::BodyDefError::None;
    const phys::BodyId id = world.add_body(to_body_def(scene.bodies[i]), &error);
    if (!id.is_valid()) {
      throw std::invalid_argument("scene " + scene.name + ": body " + std::to_string(i) +
                                  " refused: " + std::string(phys::describe(error)));
    }
    ids.push_back(id);
  }
  return ids;
}

}  // namespace scenes
