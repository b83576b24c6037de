#pragma once
// The server's world stepped in-process, for comparing with what a server sent: the
// scene built with scene::build_world, each player's body added as the server adds
// it (the scene's player definition at the position its Welcome reports), the same
// inputs clamped as the server clamps them, one world step a tick.
#include <cstdint>
#include <optional>

#include "client/types.h"
#include "physics/world.h"
#include "scene/scene.h"

namespace physics_testing {

class ReferenceRun {
 public:
  explicit ReferenceRun(const scene::SceneDef& scene);
  // Steps with no players until the world is at `tick` (the Welcome's current_tick).
  void advance_to(std::uint64_t tick);
  // Adds the body a Welcome gave its client, and returns the id the world chose: it
  // equals welcome.body_id when players are added in the order of their body ids.
  // std::invalid_argument when the Welcome does not list the client's body.
  std::uint64_t add_player(const client::Welcome& welcome);
  // The acceleration the body holds from the next step on, clamped to the scene's
  // max_acceleration as the server clamps an input.
  void set_input(std::uint64_t body_id, double ax, double ay);
  // Steps one tick; returns the state hash after it.
  std::uint64_t step();
  std::uint64_t tick() const { return tick_; }
  double dt() const { return dt_; }
  std::optional<phys::BodyState> body(std::uint64_t body_id) const;
  phys::World& world() { return world_; }

 private:
  scene::SceneDef scene_;
  phys::World world_;
  double dt_;
  std::uint64_t tick_ = 0;
};

}  // namespace physics_testing
