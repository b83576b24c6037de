#include "client/input_pacer.h"

#include <algorithm>

namespace client {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::chrono::seconds kFirstRoundTripWait{1};

InputClockConfig with_tick_rate(InputClockConfig config, const Welcome& welcome) {
  if (config.tick_rate <= 0.0) config.tick_rate = welcome.tick_rate;
  // An input further ahead than the server accepts would be refused.
  if (welcome.max_ticks_ahead > 1) {
    config.max_delay = std::min(config.max_delay, welcome.max_ticks_ahead - 1);
  }
  return config;
}

}  // namespace

InputPacer::InputPacer(Client& client, PacerConfig config)
    : client_(client),
      config_(config),
      clock_(with_tick_rate(config.clock, client.welcome())),
      lockstep_(client.welcome().lockstep),
      newest_seen_(client.welcome().current_tick),
      last_sent_(client.welcome().current_tick),
      started_(Clock::now()) {
  if (lockstep_) {
    clock_.on_waiting_at(newest_seen_);
  } else {
    clock_.on_tick_seen(newest_seen_, Clock::now());
  }
}

void InputPacer::take_pongs() {
  while (auto pong = client_.next_pong(std::chrono::milliseconds(0))) {
    if (pong->client_time_ns == 0) continue;
    const Clock::time_point sent{std::chrono::nanoseconds(pong->client_time_ns)};
    clock_.on_round_trip(pong->received_at - sent, pong->received_at);
  }
}

bool InputPacer::send_through(std::uint64_t due, const InputFor& input) {
  // A lockstep server steps nothing until every player has sent the next tick.
  if (lockstep_) due = std::max(due, newest_seen_ + 1);
  if (due <= last_sent_) return true;
  // At a fixed rate an input holds until the next: only the newest due one matters.
  const std::uint64_t first = lockstep_ ? last_sent_ + 1 : due;
  for (std::uint64_t tick = first; tick <= due; ++tick) {
    const Vec2 a = input(tick);
    if (!client_.send_input(tick, a.x, a.y)) return false;
    ++stats_.inputs_sent;
    last_sent_ = tick;
  }
  return true;
}

std::optional<Snapshot> InputPacer::poll(Clock::time_point deadline, const InputFor& input) {
  const bool on_clock = config_.schedule == InputSchedule::Clock;
  for (;;) {
    if (client_.state() != ConnectionState::Connected) return std::nullopt;
    take_pongs();
    const auto now = Clock::now();
    if (now >= next_ping_) {
      if (!client_.send_ping(next_nonce_++)) return std::nullopt;
      ++stats_.pings_sent;
      next_ping_ = now + config_.ping_interval;
    }
    // The first inputs wait for the first round trip (or a second without one): sent
    // before the lead is known, they would arrive late and teach the lead a wrong
    // lesson. A lockstep server waits for them anyway.
    const bool lead_known = clock_.round_trip() || now >= started_ + kFirstRoundTripWait;
    if (!on_clock || lead_known) {
      // After a snapshot: at first the tick after the one joined at.
      const std::uint64_t due = on_clock ? clock_.send_up_to(now) : last_sent_;
      const std::uint64_t sent_before = last_sent_;
      if (!send_through(due, input)) return std::nullopt;
      if (config_.return_after_send && last_sent_ != sent_before) return std::nullopt;
    }
    auto wake = std::min(deadline, next_ping_);
    if (on_clock) wake = std::min(wake, clock_.next_send_time(now));
    const auto wait = std::chrono::ceil<std::chrono::milliseconds>(
        std::max<Clock::duration>(wake - now, Clock::duration::zero()));
    if (auto snapshot = client_.next_snapshot(wait)) {
      newest_seen_ = std::max(newest_seen_, snapshot->tick);
      clock_.on_tick_seen(snapshot->tick, snapshot->received_at);
      if (snapshot->input_margin_us) {
        ++stats_.margins_seen;
        if (*snapshot->input_margin_us < 0) ++stats_.late_margins;
        // After each snapshot the schedule is fixed: the margins have nothing to adapt.
        if (on_clock) {
          clock_.on_margin(std::chrono::microseconds(*snapshot->input_margin_us),
                           snapshot->received_at);
        }
      }
      if (!on_clock && !send_through(snapshot->tick + config_.after_snapshot_lead, input)) {
        return std::nullopt;
      }
      return snapshot;
    }
    if (Clock::now() >= deadline) return std::nullopt;
  }
}

}  // namespace client
