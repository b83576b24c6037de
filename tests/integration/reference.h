#pragma once
// The same scene stepped in-process, for comparing against what the server sent:
// scene::build_world, the players' bodies added as the server adds them (the
// scene's player def at the position the Welcome reports), the same inputs.
#include <cstdint>
#include <map>
#include <optional>

#include "client/types.h"
#include "physics/world.h"
#include "scene/scene.h"

namespace itest {

class ReferenceRun {
 public:
  explicit ReferenceRun(const scene::SceneDef& scene);
  // Steps with no players until the world is at `tick` (the Welcome's current_tick).
  void advance_to(std::uint64_t tick);
  // Adds the body a Welcome gave its client. Returns the id the world chose, which
  // must equal welcome.body_id for the runs to be comparable.
  std::uint64_t add_player(const client::Welcome& welcome);
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

}  // namespace itest
