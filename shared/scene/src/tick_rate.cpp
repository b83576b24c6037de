#include <fmt/format.h>

#include "scene/scene.h"

namespace scene {

std::string tick_rate_problem(double rate) {
  if (is_valid_tick_rate(rate)) return "";
  return fmt::format("tick rate must be in [{}, {}] ticks per second, got {}", kMinTickRate,
                     kMaxTickRate, rate);
}

}  // namespace scene
