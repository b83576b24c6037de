#include "pattern.h"

#include <cmath>
#include <numbers>

namespace client_app {

client::Vec2 AccelerationPattern::at(std::uint64_t tick) const {
  if (constant) return *constant;
  const double turn = static_cast<double>(tick % period_ticks) / static_cast<double>(period_ticks);
  const double angle = 2.0 * std::numbers::pi * turn;
  return {magnitude * std::cos(angle), magnitude * std::sin(angle)};
}

}  // namespace client_app
