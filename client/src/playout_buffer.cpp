#include "client/playout_buffer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace client {
namespace {

bool finite(const Vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

Vec2 advance(const Vec2& position, const Vec2& velocity, double seconds) {
  return {position.x + velocity.x * seconds, position.y + velocity.y * seconds};
}

Vec2 lerp(const Vec2& a, const Vec2& b, double u) {
  return {a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u};
}

bool by_id(const BodyState& a, const BodyState& b) { return a.body_id < b.body_id; }

std::string out_of_range(const char* field, double value, const char* range) {
  return std::string(field) + " = " + std::to_string(value) + " is out of range " + range;
}

}  // namespace

std::string PlayoutSettings::validate() const {
  auto in = [](double value, double low, double high) {
    return std::isfinite(value) && value >= low && value <= high;
  };
  if (!in(tick_rate, 1e-3, 1e6) || tick_rate <= 0.0)
    return out_of_range("tick_rate", tick_rate, "(0, 1e6]");
  if (!in(send_interval, 0.0, 60.0)) return out_of_range("send_interval", send_interval, "[0, 60]");
  if (!in(send_intervals, 0.0, 100.0))
    return out_of_range("send_intervals", send_intervals, "[0, 100]");
  if (!in(jitter_multiplier, 0.0, 100.0))
    return out_of_range("jitter_multiplier", jitter_multiplier, "[0, 100]");
  if (!in(min_delay, 0.0, 60.0)) return out_of_range("min_delay", min_delay, "[0, 60]");
  if (!in(max_delay, min_delay, 60.0))
    return out_of_range("max_delay", max_delay, "[min_delay, 60]");
  if (!in(max_extrapolation, 0.0, 60.0))
    return out_of_range("max_extrapolation", max_extrapolation, "[0, 60]");
  if (!in(slew, 0.0, 1.0)) return out_of_range("slew", slew, "[0, 1]");
  if (!in(snap, 1e-6, 3600.0)) return out_of_range("snap", snap, "(0, 3600]");
  if (!in(max_gap, 1e-6, 1e9)) return out_of_range("max_gap", max_gap, "(0, 1e9]");
  if (capacity < 2 || capacity > (1u << 20))
    return "capacity = " + std::to_string(capacity) + " is out of range [2, 1048576]";
  return {};
}

const char* to_string(PushResult result) {
  switch (result) {
    case PushResult::Accepted:
      return "accepted";
    case PushResult::Reset:
      return "accepted after a reset";
    case PushResult::Stale:
      return "stale tick";
    case PushResult::BadTime:
      return "bad arrival time";
    case PushResult::BadState:
      return "bad body state";
  }
  return "unknown";
}

const char* to_string(PlayoutStatus status) {
  switch (status) {
    case PlayoutStatus::Empty:
      return "empty";
    case PlayoutStatus::Early:
      return "early";
    case PlayoutStatus::Interpolating:
      return "interpolating";
    case PlayoutStatus::Extrapolating:
      return "extrapolating";
    case PlayoutStatus::Holding:
      return "holding";
  }
  return "unknown";
}

PlayoutBuffer::PlayoutBuffer(PlayoutSettings settings) : settings_(settings) {
  const std::string problem = settings_.validate();
  if (!problem.empty()) throw std::invalid_argument("PlayoutSettings: " + problem);
}

double PlayoutBuffer::interval() const {
  return settings_.send_interval > 0.0 ? settings_.send_interval : 1.0 / settings_.tick_rate;
}

double PlayoutBuffer::delay() const {
  const double wanted =
      settings_.send_intervals * interval() + settings_.jitter_multiplier * jitter_;
  return std::clamp(wanted, settings_.min_delay, settings_.max_delay);
}

void PlayoutBuffer::clear() {
  held_.clear();
  still_ids_.clear();
  jitter_ = 0.0;
  offset_ = 0.0;
  has_shown_ = false;
}

void PlayoutBuffer::recompute_offset() {
  offset_ = held_.front().transit;
  for (const Held& held : held_) offset_ = std::min(offset_, held.transit);
}

PushResult PlayoutBuffer::push(const Snapshot& snapshot, double arrival_time) {
  if (!std::isfinite(arrival_time)) {
    ++stats_.bad_time;
    return PushResult::BadTime;
  }
  for (const BodyState& body : snapshot.bodies) {
    if (!finite(body.position) || !finite(body.velocity)) {
      ++stats_.bad_state;
      return PushResult::BadState;
    }
  }
  if (!held_.empty() && snapshot.tick <= held_.back().snapshot.tick) {
    ++stats_.stale;
    return PushResult::Stale;
  }
  if (has_arrival_ && arrival_time < last_arrival_) {
    ++stats_.clock_backwards;
    arrival_time = last_arrival_;
  }
  const double server_time = static_cast<double>(snapshot.tick) / settings_.tick_rate;
  PushResult result = PushResult::Accepted;
  if (!held_.empty() && server_time - held_.back().server_time > settings_.max_gap) {
    clear();
    ++stats_.resets;
    result = PushResult::Reset;
  }
  const double transit = arrival_time - server_time;
  if (!held_.empty()) {
    // RFC 3550, section 6.4.1: J += (|D| - J) / 16.
    const double change = std::abs(transit - held_.back().transit);
    jitter_ += (change - jitter_) / 16.0;
  }
  held_.push_back({snapshot, server_time, transit});
  std::vector<BodyState>& bodies = held_.back().snapshot.bodies;
  if (!std::is_sorted(bodies.begin(), bodies.end(), by_id))
    std::sort(bodies.begin(), bodies.end(), by_id);
  if (held_.size() > settings_.capacity) {
    held_.pop_front();
    ++stats_.dropped;
  }
  recompute_offset();

  still_ids_.clear();
  if (held_.size() >= 2) {
    const Snapshot& before = held_[held_.size() - 2].snapshot;
    for (const BodyState& body : bodies) {
      const auto it = std::lower_bound(before.bodies.begin(), before.bodies.end(), body, by_id);
      if (it != before.bodies.end() && *it == body) still_ids_.push_back(body.body_id);
    }
  }
  last_arrival_ = arrival_time;
  has_arrival_ = true;
  ++stats_.accepted;
  return result;
}

const PlayoutFrame& PlayoutBuffer::state_at(double now) {
  if (!std::isfinite(now) || (has_now_ && now < last_now_)) {
    ++stats_.clock_backwards;
    now = has_now_ ? last_now_ : 0.0;
  }
  const double elapsed = has_now_ ? now - last_now_ : 0.0;
  last_now_ = now;
  has_now_ = true;
  if (held_.empty()) {
    frame_ = PlayoutFrame{};
    return frame_;
  }
  const double target = now - offset_ - delay();
  if (!has_shown_ || std::abs(target - (shown_ + elapsed)) > settings_.snap) {
    if (has_shown_) ++stats_.snaps;
    shown_ = target;
    has_shown_ = true;
  } else {
    shown_ += elapsed;
    const double step = settings_.slew * elapsed;
    shown_ += std::clamp(target - shown_, -step, step);
  }
  fill(shown_);
  frame_.lag = (now - offset_) - shown_;
  return frame_;
}

const PlayoutFrame& PlayoutBuffer::state_at_server_time(double server_time) {
  if (held_.empty() || !std::isfinite(server_time)) {
    if (held_.empty()) frame_ = PlayoutFrame{};
    return frame_;
  }
  fill(server_time);
  frame_.lag = held_.back().server_time - server_time;
  return frame_;
}

void PlayoutBuffer::fill(double shown) {
  frame_.server_time = shown;
  frame_.newest_tick = held_.back().snapshot.tick;
  frame_.extrapolated = 0.0;
  frame_.bodies.clear();
  auto is_still = [&](std::uint64_t id) {
    return std::binary_search(still_ids_.begin(), still_ids_.end(), id);
  };
  auto emit = [&](const BodyState& body, Vec2 position, Vec2 velocity) {
    frame_.bodies.push_back(
        {body.body_id, position, velocity, is_still(body.body_id), body.motion});
  };

  const Held& newest = held_.back();
  if (shown > newest.server_time) {
    const double past = shown - newest.server_time;
    frame_.status =
        past <= settings_.max_extrapolation ? PlayoutStatus::Extrapolating : PlayoutStatus::Holding;
    frame_.extrapolated = past;
    const double carried = std::min(past, settings_.max_extrapolation);
    for (const BodyState& body : newest.snapshot.bodies)
      emit(body, advance(body.position, body.velocity, carried), body.velocity);
    return;
  }
  const Held& oldest = held_.front();
  if (shown < oldest.server_time) {
    frame_.status = PlayoutStatus::Early;
    for (const BodyState& body : oldest.snapshot.bodies) emit(body, body.position, body.velocity);
    return;
  }
  // The snapshot after the shown time: the first held later than it.
  const auto after =
      std::upper_bound(held_.begin(), held_.end(), shown,
                       [](double time, const Held& held) { return time < held.server_time; });
  if (after == held_.end()) {
    // shown equals the newest server time exactly.
    frame_.status = PlayoutStatus::Interpolating;
    for (const BodyState& body : newest.snapshot.bodies) emit(body, body.position, body.velocity);
    return;
  }
  const Held& b = *after;
  const Held& a = *(after - 1);
  frame_.status = PlayoutStatus::Interpolating;
  // Over a gap of more than one send interval the earlier snapshot is carried at
  // its velocity until one interval before the later one, then interpolated.
  const double start = std::max(a.server_time, b.server_time - interval());
  const double span = b.server_time - start;
  const double u = shown <= start ? 0.0 : (shown - start) / span;
  const double carried = std::min(shown, start) - a.server_time;
  const std::vector<BodyState>& from = a.snapshot.bodies;
  const std::vector<BodyState>& to = b.snapshot.bodies;
  auto j = to.begin();
  for (const BodyState& body : from) {
    while (j != to.end() && j->body_id < body.body_id) ++j;
    const Vec2 carried_to = advance(body.position, body.velocity, carried);
    if (j == to.end() || j->body_id != body.body_id) {
      // Gone in the later snapshot: shown as the earlier one carries it, until then.
      const double past = std::min(shown - a.server_time, settings_.max_extrapolation);
      emit(body, advance(body.position, body.velocity, past), body.velocity);
      continue;
    }
    emit(body, lerp(carried_to, j->position, u), lerp(body.velocity, j->velocity, u));
  }
  // Bodies new in the later snapshot appear once the shown time reaches it.
}

}  // namespace client
