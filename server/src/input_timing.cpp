#include "input_timing.h"

#include <algorithm>

namespace server {

InputTiming::InputTiming(std::chrono::nanoseconds period, std::chrono::nanoseconds idle_gap)
    : period_(period), idle_gap_(idle_gap) {}

void InputTiming::arrived(ClientId client, std::uint64_t tick, time_point at) {
  Client& c = clients_[client];
  if (last_tick_ && tick <= *last_tick_) {
    // Late: its tick was due at the last tick's due time less the ticks between.
    const auto ticks_before = static_cast<std::int64_t>(*last_tick_ - tick);
    const time_point due = last_due_ - period_ * ticks_before;
    c.note(due - at);
    return;
  }
  // At most max_ticks_ahead + 1 entries: inputs further ahead are refused before.
  c.waiting[tick] = at;
}

InputTiming::time_point InputTiming::stepped(std::uint64_t tick,
                                             std::optional<time_point> scheduled) {
  std::optional<time_point> first;
  for (auto& [id, c] : clients_) {
    const auto it = c.waiting.find(tick);
    if (it != c.waiting.end() && (!first || it->second < *first)) first = it->second;
  }
  time_point due = scheduled.value_or(first.value_or(time_point{}));
  if (first && (!scheduled || *first - *scheduled > idle_gap_)) due = *first;
  for (auto& [id, c] : clients_) {
    const auto it = c.waiting.find(tick);
    if (it != c.waiting.end()) c.note(due - it->second);
    c.waiting.erase(c.waiting.begin(), c.waiting.upper_bound(tick));
  }
  last_tick_ = tick;
  last_due_ = due;
  return due;
}

std::optional<std::chrono::microseconds> InputTiming::take_least_margin(ClientId client) {
  const auto it = clients_.find(client);
  if (it == clients_.end() || !it->second.least) return std::nullopt;
  const auto least = std::chrono::duration_cast<std::chrono::microseconds>(*it->second.least);
  it->second.least.reset();
  return least;
}

}  // namespace server
