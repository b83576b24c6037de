#include "physics/fixed_timestep.h"

#include <cassert>
#include <cmath>

namespace phys {

namespace {
std::chrono::nanoseconds period_of(double tick_rate_hz) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(1.0e9 / tick_rate_hz)));
}
}  // namespace

FixedTimestep::FixedTimestep(const Clock& clock, FixedTimestepConfig config)
    : clock_(clock),
      dt_(1.0 / config.tick_rate_hz),
      period_(period_of(config.tick_rate_hz)),
      max_steps_(config.max_steps_per_frame),
      last_(clock.now()) {
  assert(config.tick_rate_hz >= kMinTickRate && config.tick_rate_hz <= kMaxTickRate);
  assert(config.max_steps_per_frame >= 1);
}

FrameResult FixedTimestep::frame(const Update& update) {
  const Clock::time_point now = clock_.now();
  // A clock that goes backwards (it should not, but a fake one may) adds nothing.
  if (now > last_) accumulator_ += now - last_;
  last_ = now;

  FrameResult result;
  while (accumulator_ >= period_ && result.steps < max_steps_) {
    update(dt_);
    accumulator_ -= period_;
    ++result.steps;
  }
  // The cap was hit: drop the whole steps still owed, keep the fraction, so the
  // next frame starts from real time instead of chasing a backlog forever.
  if (accumulator_ >= period_) {
    const auto owed = static_cast<std::uint64_t>(accumulator_ / period_);
    result.dropped_steps = owed;
    accumulator_ -= period_ * static_cast<std::int64_t>(owed);
  }
  total_steps_ += static_cast<std::uint64_t>(result.steps);
  total_dropped_ += result.dropped_steps;
  return result;
}

double FixedTimestep::alpha() const {
  return static_cast<double>(accumulator_.count()) / static_cast<double>(period_.count());
}

Clock::time_point FixedTimestep::next_step_due() const { return last_ + (period_ - accumulator_); }

}  // namespace phys
