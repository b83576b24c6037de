#include "server/input_buffer.h"

#include <algorithm>
#include <cmath>

namespace server {
namespace {

// Spans up to this many ticks keep the deque's index between inputs (an honest
// client's span is a few ticks); larger ones give it back once emptied.
constexpr std::size_t kLargeSpan = 4096;

}  // namespace

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
  if (slots_.empty()) {
    first_tick_ = apply_at;
    slots_.emplace_back();
  } else if (apply_at < first_tick_) {
    // Earlier than every pending input: grow at the front, one slot a tick.
    slots_.insert(slots_.begin(), first_tick_ - apply_at, Slot{});
    first_tick_ = apply_at;
  } else if (apply_at - first_tick_ >= slots_.size()) {
    slots_.resize(apply_at - first_tick_ + 1);
  }
  peak_slots_ = std::max(peak_slots_, slots_.size());
  Slot& slot = slots_[apply_at - first_tick_];
  if (!slot.present) {
    slot = Slot{named_tick, acceleration, true};
    ++pending_;
  } else if (named_tick >= slot.named_tick) {
    slot.named_tick = named_tick;
    slot.acceleration = acceleration;
  }
}

bool ClientInputs::has_input_for(std::uint64_t tick) const {
  // Anything due at or before `tick` counts: it will be applied when `tick` steps.
  return !slots_.empty() && first_tick_ <= tick;
}

ClientInputs::Taken ClientInputs::take(std::uint64_t tick) {
  Taken taken;
  while (!slots_.empty() && first_tick_ <= tick) {
    const Slot& slot = slots_.front();
    if (slot.present) {
      held_ = slot.acceleration;
      last_applied_tick_ = slot.named_tick;
      has_applied_ = true;
      taken.fresh = true;
      --pending_;
    }
    slots_.pop_front();
    ++first_tick_;
  }
  // Empty ticks before the next input are not kept: the front is always an input.
  while (!slots_.empty() && !slots_.front().present) {
    slots_.pop_front();
    ++first_tick_;
  }
  // The deque frees its blocks as they empty, but keeps its index of them (8 bytes a
  // block of 16 slots): after a large span, start afresh.
  if (slots_.empty() && peak_slots_ > kLargeSpan) {
    std::deque<Slot>().swap(slots_);
    peak_slots_ = 0;
  }
  taken.acceleration = held_;
  return taken;
}

}  // namespace server
