#include "client/input_clock.h"

#include <algorithm>
#include <cmath>

namespace client {
namespace {

using std::chrono::nanoseconds;

constexpr std::chrono::seconds kTripMemory{2};
// How fast the arrival offset follows a later one: 1/16 of the difference a snapshot,
// a time constant of 16 snapshots (about a quarter second at 60 Hz).
constexpr std::int64_t kOffsetRise = 16;
constexpr std::chrono::seconds kLowerWindow{1};
constexpr std::size_t kMaxSamples = 256;

double ratio(nanoseconds a, nanoseconds b) {
  return static_cast<double>(a.count()) / static_cast<double>(b.count());
}

}  // namespace

InputClock::InputClock(InputClockConfig config)
    : config_(config),
      period_(std::chrono::duration_cast<nanoseconds>(
          std::chrono::duration<double>(1.0 / std::max(config.tick_rate, 1e-3)))) {
  lead_chosen_ = config_.fixed_delay.has_value();
}

void InputClock::on_tick_seen(std::uint64_t tick, time_point received) {
  if (!base_tick_) base_tick_ = tick;
  // Ticks before the first one seen (a reordered heartbeat) count as negative.
  const double ticks = static_cast<double>(tick) - static_cast<double>(*base_tick_);
  const auto since = std::chrono::duration_cast<nanoseconds>(
      std::chrono::duration<double, std::nano>(ticks * static_cast<double>(period_.count())));
  const std::chrono::nanoseconds offset = received.time_since_epoch() - since;
  // An earlier arrival is taken at once (jitter and queueing only add delay); a later
  // one is followed slowly, so that jitter barely moves the estimate and a server
  // that fell behind (a stall, a lockstep tick that waited) is followed within a
  // quarter second.
  if (!offset_ || offset < *offset_) {
    offset_ = offset;
  } else {
    *offset_ += (offset - *offset_) / kOffsetRise;
  }
  waiting_at_.reset();
}

void InputClock::on_waiting_at(std::uint64_t tick) {
  if (!offset_) waiting_at_ = tick;
}

void InputClock::on_round_trip(nanoseconds round_trip, time_point received) {
  if (round_trip.count() < 0) return;
  trips_.push_back({received, round_trip});
  while (trips_.size() > kMaxSamples ||
         (trips_.size() > 1 && trips_.front().received + kTripMemory < received)) {
    trips_.pop_front();
  }
  if (!lead_chosen_) {
    // A whole round trip ahead of the tick seen is half of one ahead of the server on
    // a symmetric path; the margins the server reports correct what that guess misses.
    ahead_ = std::min(round_trip + nanoseconds(config_.safety), max_ahead());
    lead_chosen_ = true;
    lower_window_start_ = received;
  }
}

void InputClock::on_margin(std::chrono::microseconds margin_us, time_point received) {
  if (config_.fixed_delay || !lead_chosen_) return;
  const nanoseconds margin(margin_us);
  const nanoseconds safety(config_.safety);
  if (margin < safety) {
    if (received >= raise_settles_) {
      ahead_ = std::min(ahead_ + (safety - margin), max_ahead());
      ++raises_;
      raise_settles_ = received + round_trip().value_or(nanoseconds{0}) + 2 * period_;
    }
    lower_window_start_ = received;
    least_in_window_.reset();
    return;
  }
  if (!least_in_window_ || margin < *least_in_window_) least_in_window_ = margin;
  if (received - lower_window_start_ < kLowerWindow) return;
  // Every input of the window arrived with more than an eighth of a tick to spare: give
  // back half of the spare.
  const nanoseconds spare = *least_in_window_ - safety;
  if (spare > period_ / 8) {
    ahead_ = std::max(nanoseconds{0}, ahead_ - spare / 2);
    ++lowers_;
  }
  lower_window_start_ = received;
  least_in_window_.reset();
}

nanoseconds InputClock::one_way() const {
  const auto trip = round_trip();
  return trip ? *trip / 2 : nanoseconds{0};
}

nanoseconds InputClock::max_ahead() const { return period_ * config_.max_delay + one_way(); }

nanoseconds InputClock::ahead() const {
  if (config_.fixed_delay)
    return period_ * std::min(*config_.fixed_delay, config_.max_delay) + one_way();
  return ahead_;
}

nanoseconds InputClock::lead() const { return std::max(nanoseconds{0}, ahead() - one_way()); }

std::optional<nanoseconds> InputClock::round_trip() const {
  if (trips_.empty()) return std::nullopt;
  return std::min_element(trips_.begin(), trips_.end(),
                          [](const Trip& a, const Trip& b) { return a.round_trip < b.round_trip; })
      ->round_trip;
}

double InputClock::seen_tick(time_point now) const {
  return static_cast<double>(*base_tick_) + ratio(now.time_since_epoch() - *offset_, period_);
}

double InputClock::server_tick(time_point now) const {
  if (!offset_) return waiting_at_ ? static_cast<double>(*waiting_at_) : 0.0;
  return seen_tick(now) + ratio(one_way(), period_);
}

// Where the inputs sent by `now` reach: the tick seen plus the round trip and margin,
// or, while a lockstep server waits, its tick plus the lead.
double InputClock::send_position(time_point now) const {
  if (!offset_) return server_tick(now) + ratio(lead(), period_);
  return seen_tick(now) + ratio(ahead(), period_);
}

std::uint64_t InputClock::send_up_to(time_point now) const {
  const double tick = send_position(now);
  return tick <= 0.0 ? 0 : static_cast<std::uint64_t>(std::floor(tick));
}

InputClock::time_point InputClock::next_send_time(time_point now) const {
  if (!offset_) return now + period_;
  const double tick = send_position(now);
  const double left = std::floor(tick) + 1.0 - tick;  // (0, 1]
  return now + std::chrono::duration_cast<nanoseconds>(std::chrono::duration<double, std::nano>(
                   left * static_cast<double>(period_.count())));
}

std::uint32_t InputClock::delay() const {
  return static_cast<std::uint32_t>(std::ceil(ratio(lead(), period_) - 1e-9));
}

}  // namespace client
