#pragma once
// The world after a tick as the snapshot side reads it: every moving body's exact
// state (dynamic and kinematic: the bodies whose state a tick can change), in
// ascending id, read from the world once per tick and shared by every
// view. A body's state a tick before lets a view see which predictor would have
// carried it over the last tick.
#include <cstdint>
#include <vector>

#include "physics/vec2.h"
#include "physics/world.h"

namespace server {

struct TruthBody {
  std::uint64_t id = 0;
  double x = 0.0;
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  bool awake = true;
  // Moved by its velocity alone (Motion::Kinematic): the Glide predictor carries it.
  bool kinematic = false;
  // The state one tick before (equal to this one for a body new this tick).
  double previous_x = 0.0;
  double previous_y = 0.0;
  double previous_vx = 0.0;
  double previous_vy = 0.0;
};

struct TruthFrame {
  std::uint64_t tick = 0;
  std::uint64_t state_hash = 0;
  std::vector<TruthBody> bodies;  // dynamic and kinematic bodies, ascending id
  // The tick's contact events (while the world produces them), step set to `tick`.
  std::vector<phys::ContactEvent> contact_events;
  // The tick's sensor events (always produced), step set to `tick`.
  std::vector<phys::SensorEvent> sensor_events;

  const TruthBody* find(std::uint64_t id) const;
};

// Reads the world after `tick`. `previous` is the frame of the tick before (or
// null), from which each body's state a tick before is taken.
TruthFrame read_truth(const phys::World& world, std::uint64_t tick, const TruthFrame* previous);

}  // namespace server
