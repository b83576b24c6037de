#pragma once
// Sensor events: a body beginning or ending to overlap a sensor (BodyDef::is_sensor),
// produced by the step itself, so that they are as reproducible as the state.
//
// Overlap. After each step, a sensor and a visitor overlap when their shapes share
// interior (touching edges do not count) and their filters let them collide
// (should_collide). A visitor is any body that is not a sensor, of any motion:
// sensors do not detect each other. Overlap is judged on the positions at the end
// of the step only: a body that crosses a sensor within one step is not seen.
// Begin: the first step a pair overlaps. End: the first step it does not, or the
// step after either body was removed.
#include <cstdint>

#include "physics/body.h"

namespace phys {

enum class SensorEventKind : std::uint8_t { Begin, End };

struct SensorEvent {
  SensorEventKind kind = SensorEventKind::Begin;
  // World::step_count() after the step that produced it (the first step is 1).
  std::uint64_t step = 0;
  BodyId sensor;
  BodyId visitor;

  bool operator==(const SensorEvent&) const = default;
};

}  // namespace phys
