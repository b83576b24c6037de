#include "client/input_clock.h"

#include <algorithm>
#include <cmath>

namespace client {
namespace {

using std::chrono::nanoseconds;

constexpr std::chrono::seconds kSeenMemory{1};
constexpr std::chrono::seconds kTripMemory{10};
constexpr std::chrono::seconds kLowerWindow{2};
constexpr std::size_t kMaxSamples = 256;

double ratio(nanoseconds a, nanoseconds b) {
  return static_cast<double>(a.count()) / static_cast<double>(b.count());
}

}  // namespace

InputClock::InputClock(InputClockConfig config)
    : config_(config),
      period_(std::chrono::duration_cast<nanoseconds>(
          std::chrono::duration<double>(1.0 / std::max(config.tick_rate, 1e-3)))) {
  if (config_.fixed_delay) {
    lead_ = period_ * std::min(*config_.fixed_delay, config_.max_delay);
    lead_chosen_ = true;
  }
}

void InputClock::on_tick_seen(std::uint64_t tick, time_point received) {
  if (!base_tick_) base_tick_ = tick;
  // Ticks before the first one seen (a reordered heartbeat) count as negative.
  const double ticks = static_cast<double>(tick) - static_cast<double>(*base_tick_);
  const auto since = std::chrono::duration_cast<nanoseconds>(
      std::chrono::duration<double, std::nano>(ticks * static_cast<double>(period_.count())));
  seen_.push_back({received, received.time_since_epoch() - since});
  while (seen_.size() > kMaxSamples ||
         (seen_.size() > 1 && seen_.front().received + kSeenMemory < received)) {
    seen_.pop_front();
  }
  waiting_at_.reset();
}

void InputClock::on_waiting_at(std::uint64_t tick) {
  if (seen_.empty()) waiting_at_ = tick;
}

void InputClock::on_round_trip(nanoseconds round_trip, time_point received) {
  if (round_trip.count() < 0) return;
  trips_.push_back({received, round_trip});
  while (trips_.size() > kMaxSamples ||
         (trips_.size() > 1 && trips_.front().received + kTripMemory < received)) {
    trips_.pop_front();
  }
  if (!lead_chosen_) {
    // Half the round trip is the one-way delay of a symmetric path; the margins the
    // server reports correct what that guess misses.
    lead_ = std::min(one_way() + nanoseconds(config_.safety), max_lead());
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
      lead_ = std::min(lead_ + (safety - margin), max_lead());
      ++raises_;
      raise_settles_ = received + round_trip().value_or(nanoseconds{0}) + 2 * period_;
    }
    lower_window_start_ = received;
    least_in_window_.reset();
    return;
  }
  if (!least_in_window_ || margin < *least_in_window_) least_in_window_ = margin;
  if (received - lower_window_start_ < kLowerWindow) return;
  // Every input of the window arrived with more than a quarter tick to spare: give
  // back half of the spare.
  const nanoseconds spare = *least_in_window_ - safety;
  if (spare > period_ / 4) {
    lead_ = std::max(nanoseconds{0}, lead_ - spare / 2);
    ++lowers_;
  }
  lower_window_start_ = received;
  least_in_window_.reset();
}

nanoseconds InputClock::one_way() const {
  const auto trip = round_trip();
  return trip ? *trip / 2 : nanoseconds{0};
}

nanoseconds InputClock::max_lead() const { return period_ * config_.max_delay; }

std::optional<nanoseconds> InputClock::round_trip() const {
  if (trips_.empty()) return std::nullopt;
  return std::min_element(trips_.begin(), trips_.end(),
                          [](const Trip& a, const Trip& b) { return a.round_trip < b.round_trip; })
      ->round_trip;
}

double InputClock::server_tick(time_point now) const {
  if (seen_.empty()) return waiting_at_ ? static_cast<double>(*waiting_at_) : 0.0;
  // The least delayed snapshot of the last second: jitter and queueing only add delay.
  const nanoseconds least =
      std::min_element(seen_.begin(), seen_.end(), [](const Seen& a, const Seen& b) {
        return a.offset < b.offset;
      })->offset;
  const nanoseconds stepped_base = least - one_way();
  return static_cast<double>(*base_tick_) + ratio(now.time_since_epoch() - stepped_base, period_);
}

std::uint64_t InputClock::send_up_to(time_point now) const {
  const double tick = server_tick(now) + ratio(lead_, period_);
  return tick <= 0.0 ? 0 : static_cast<std::uint64_t>(std::floor(tick));
}

InputClock::time_point InputClock::next_send_time(time_point now) const {
  if (seen_.empty()) return now + period_;
  const double tick = server_tick(now) + ratio(lead_, period_);
  const double left = std::floor(tick) + 1.0 - tick;  // (0, 1]
  return now + std::chrono::duration_cast<nanoseconds>(std::chrono::duration<double, std::nano>(
                   left * static_cast<double>(period_.count())));
}

std::uint32_t InputClock::delay() const {
  return static_cast<std::uint32_t>(std::ceil(ratio(lead_, period_) - 1e-9));
}

}  // namespace client
