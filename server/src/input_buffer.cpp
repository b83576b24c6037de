#include "server/input_buffer.h"

#include <algorithm>
#include <cmath>

namespace server {

InputCheck check_input(std::uint64_t tick, phys::Vec2 acceleration, std::uint64_t current_tick,
                       std::uint64_t max_ticks_ahead, double max_acceleration) {
  InputCheck check;
  if (!phys::is_finite(acceleration)) {
    check.verdict = InputVerdict::NonFinite;
    return check;
  }
  // Written as a subtraction so that a tick near 2^64 cannot wrap the sum around.
  if (tick > current_tick && tick - current_tick > max_ticks_ahead) {
    check.verdict = InputVerdict::TooFarAhead;
    return check;
  }
  check.acceleration = phys::clamp_length(acceleration, max_acceleration, &check.clamped);
  if (tick <= current_tick) {
    check.verdict = InputVerdict::Late;
    check.apply_at = current_tick + 1;
  } else {
    check.verdict = InputVerdict::OnTime;
    check.apply_at = tick;
  }
  return check;
}

void ClientInputs::file(std::uint64_t apply_at, std::uint64_t named_tick, phys::Vec2 acceleration) {
  auto [it, inserted] = pending_.try_emplace(apply_at, Pending{named_tick, acceleration});
  if (!inserted && named_tick >= it->second.named_tick) {
    it->second = Pending{named_tick, acceleration};
  }
}

bool ClientInputs::has_input_for(std::uint64_t tick) const {
  // Anything due at or before `tick` counts: it will be applied when `tick` steps.
  return !pending_.empty() && pending_.begin()->first <= tick;
}

ClientInputs::Taken ClientInputs::take(std::uint64_t tick) {
  Taken taken;
  auto it = pending_.begin();
  while (it != pending_.end() && it->first <= tick) {
    held_ = it->second.acceleration;
    last_applied_tick_ = it->second.named_tick;
    has_applied_ = true;
    taken.fresh = true;
    it = pending_.erase(it);
  }
  taken.acceleration = held_;
  return taken;
}

}  // namespace server
