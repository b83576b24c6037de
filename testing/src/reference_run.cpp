#include "physics_testing/reference_run.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "physics/vec2.h"

namespace physics_testing {

ReferenceRun::ReferenceRun(const scene::SceneDef& scene)
    : scene_(scene), world_(scene::build_world(scene)), dt_(1.0 / scene.tick_rate) {}

void ReferenceRun::advance_to(std::uint64_t tick) {
  while (tick_ < tick) step();
}

std::uint64_t ReferenceRun::add_player(const client::Welcome& welcome) {
  const auto it = std::find_if(
      welcome.bodies.begin(), welcome.bodies.end(),
      [&](const client::BodyShape& shape) { return shape.body_id == welcome.body_id; });
  if (it == welcome.bodies.end()) {
    throw std::invalid_argument("the Welcome does not list the client's body " +
                                std::to_string(welcome.body_id));
  }
  phys::BodyDef def = scene_.player;
  def.position = {it->position.x, it->position.y};
  return world_.add_body(def).packed();
}

void ReferenceRun::set_input(std::uint64_t body_id, double ax, double ay) {
  world_.set_acceleration(phys::BodyId::from_packed(body_id),
                          phys::clamp_length({ax, ay}, scene_.max_acceleration));
}

std::uint64_t ReferenceRun::step() {
  world_.step(dt_);
  ++tick_;
  return world_.state_hash();
}

std::optional<phys::BodyState> ReferenceRun::body(std::uint64_t body_id) const {
  return world_.body(phys::BodyId::from_packed(body_id));
}

}  // namespace physics_testing
