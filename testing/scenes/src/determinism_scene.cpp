#include "scenes/determinism_scene.h"

#include <stdexcept>
#include <string>

namespace scenes {
namespace {

phys::BodyDef box_def(phys::Vec2 center, phys::Vec2 half_extents, phys::Motion motion) {
  phys::BodyDef def;
  def.shape = phys::Shape::Box;
  def.motion = motion;
  def.position = center;
  def.half_extents = half_extents;
  return def;
}

phys::BodyDef circle_def(phys::Vec2 center, double radius, phys::Motion motion) {
  phys::BodyDef def;
  def.shape = phys::Shape::Circle;
  def.motion = motion;
  def.position = center;
  def.radius = radius;
  return def;
}

phys::BodyId add(phys::World& world, const phys::BodyDef& def) {
  phys::BodyDefError error = phys::BodyDefError::None;
  const phys::BodyId id = world.add_body(def, &error);
  if (!id.is_valid())
    throw std::invalid_argument("determinism scene: body refused: " +
                                std::string(phys::describe(error)));
  return id;
}

}  // namespace

std::vector<phys::BodyId> add_determinism_scene(phys::World& world) {
  using phys::Motion;
  std::vector<phys::BodyId> dynamic;
  add(world, box_def({0.0, -0.5}, {20.0, 0.5}, Motion::Static));
  add(world, box_def({-20.5, 10.0}, {0.5, 10.0}, Motion::Static));
  add(world, box_def({20.5, 10.0}, {0.5, 10.0}, Motion::Static));
  for (int i = 0; i < 4; ++i) {
    add(world, box_def({-10.0 + 2.0 * i, 0.25 + 0.5 * i}, {1.0, 0.25 + 0.5 * i}, Motion::Static));
  }
  add(world, circle_def({8.0, 3.0}, 1.0, Motion::Static));
  for (int i = 0; i < 40; ++i) {
    const double x = -15.0 + 0.75 * i;
    const double y = 4.0 + 1.5 * (i % 5);
    phys::BodyDef def =
        (i % 3 == 0)
            ? circle_def({x, y}, 0.3 + 0.05 * (i % 4), Motion::Dynamic)
            : box_def({x, y}, {0.3 + 0.04 * (i % 5), 0.25 + 0.03 * (i % 3)}, Motion::Dynamic);
    def.mass = 0.5 + 0.25 * (i % 7);
    def.restitution = 0.1 * (i % 6);
    def.friction = {0.2 * (i % 4), 0.0};
    // Integer patterns, not sin/cos: the scene itself must not depend on libm.
    def.velocity = {1.25 * ((i * 7) % 11 - 5), 1.0 * ((i * 5) % 9 - 4)};
    dynamic.push_back(add(world, def));
  }
  return dynamic;
}

void apply_determinism_inputs(phys::World& world, const std::vector<phys::BodyId>& dynamic,
                              int step) {
  if (step % 50 == 0) {
    const double direction = (step / 50) % 2 == 0 ? 1.0 : -1.0;
    world.set_acceleration(dynamic[0], {8.0 * direction, 0.0});
  }
  if (step == 500) {
    world.remove_body(dynamic[7]);
    phys::BodyDef def = circle_def({0.0, 15.0}, 0.4, phys::Motion::Dynamic);
    def.restitution = 0.6;
    add(world, def);
  }
}

}  // namespace scenes
