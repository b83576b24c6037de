#pragma once
// What acceleration physics-client sends for a tick: the one given with --accel,
// or, without it, a scripted circle so that the body visibly moves around.
#include <cstdint>
#include <optional>

#include "client/types.h"

namespace client_app {

struct AccelerationPattern {
  std::optional<client::Vec2> constant;  // --accel X,Y
  double magnitude = 5.0;                // of the circle, m/s^2
  std::uint64_t period_ticks = 120;      // one turn of the circle

  client::Vec2 at(std::uint64_t tick) const;
};

}  // namespace client_app
