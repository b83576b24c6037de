#include "replay_world.h"

#include <SDL.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace viewer {

ReplayWorld::ReplayWorld(client::ClientRecording recording, std::string name, double speed)
    : recording_(std::move(recording)), name_(std::move(name)) {
  settings_.tick_rate = recording_.welcome.tick_rate;
  settings_.send_interval = recording_.welcome.view.snapshot_interval / settings_.tick_rate;
  set_speed(speed);
  restart();
  time_ = time_of(0);
}

double ReplayWorld::time_of(std::size_t index) const {
  return static_cast<double>(recording_.snapshots[index].snapshot.tick) / settings_.tick_rate;
}

std::size_t ReplayWorld::index_at(double server_time) const {
  // A shown time a rounding error short of a snapshot's counts as at it: the time
  // is summed from clock readings, the snapshots' from tick / tick_rate.
  const double at = server_time + kSameTime / settings_.tick_rate;
  const auto& all = recording_.snapshots;
  const auto after = std::upper_bound(
      all.begin(), all.end(), at, [&](double t, const client::RecordedSnapshot& s) {
        return t < static_cast<double>(s.snapshot.tick) / settings_.tick_rate;
      });
  return after == all.begin() ? 0 : static_cast<std::size_t>(after - all.begin()) - 1;
}

void ReplayWorld::restart() {
  buffer_.emplace(settings_);
  shapes_.reset(recording_.welcome.bodies);
  fed_ = 0;
}

void ReplayWorld::feed_to(double server_time) {
  // The buffer holds snapshots [fed_ - size, fed_). Going back before them: start
  // again from the Welcome, so that shapes added and removed are replayed in order.
  const std::size_t at = index_at(server_time);
  if (fed_ > 0 && at < fed_ - buffer_->size()) restart();
  // The snapshot after the shown time too: the buffer interpolates toward it.
  const std::size_t wanted = std::min(at + 2, recording_.snapshots.size());
  while (fed_ < wanted) {
    const client::RecordedSnapshot& next = recording_.snapshots[fed_];
    shapes_.apply(next.snapshot);
    buffer_->push(next.snapshot, next.arrival);
    ++fed_;
  }
}

const client::PlayoutFrame& ReplayWorld::update(double now) {
  const double elapsed = has_now_ && now > last_now_ ? now - last_now_ : 0.0;
  last_now_ = now;
  has_now_ = true;
  if (!paused_) {
    time_ += elapsed * speed_;
    const double end = time_of(recording_.snapshots.size() - 1);
    if (time_ >= end) {
      time_ = end;
      paused_ = true;  // at the end: stopped there
    }
  }
  feed_to(time_);
  return buffer_->state_at_server_time(time_);
}

void ReplayWorld::step(int direction) {
  paused_ = true;
  const std::size_t at = index_at(time_);
  const bool on_it = std::abs(time_of(at) - time_) <= kSameTime / settings_.tick_rate;
  if (direction > 0) {
    time_ = time_of(std::min(at + 1, recording_.snapshots.size() - 1));
  } else if (direction < 0) {
    // Between two snapshots, back is the earlier of them.
    time_ = time_of(on_it && at > 0 ? at - 1 : at);
  }
}

void ReplayWorld::seek(double server_time) {
  if (!std::isfinite(server_time)) return;
  time_ = std::clamp(server_time, time_of(0), time_of(recording_.snapshots.size() - 1));
}

void ReplayWorld::seek_tick(std::uint64_t tick) {
  const auto& all = recording_.snapshots;
  const auto it = std::find_if(all.begin(), all.end(), [&](const client::RecordedSnapshot& s) {
    return s.snapshot.tick >= tick;
  });
  time_ = time_of(it == all.end() ? all.size() - 1 : static_cast<std::size_t>(it - all.begin()));
}

void ReplayWorld::set_speed(double speed) {
  speed_ = std::isfinite(speed) ? std::clamp(speed, kMinSpeed, kMaxSpeed) : 1.0;
}

const client::Snapshot& ReplayWorld::current() const {
  return recording_.snapshots[index_at(time_)].snapshot;
}

bool ReplayWorld::key(int keycode) {
  switch (keycode) {
    case SDLK_SPACE:
      if (paused_ && time_ >= time_of(recording_.snapshots.size() - 1)) time_ = time_of(0);
      paused_ = !paused_;
      return true;
    case SDLK_PERIOD:
      step(+1);
      return true;
    case SDLK_COMMA:
      step(-1);
      return true;
    case SDLK_RIGHTBRACKET:
      set_speed(speed_ * 2.0);
      return true;
    case SDLK_LEFTBRACKET:
      set_speed(speed_ / 2.0);
      return true;
    case SDLK_PAGEDOWN:
      seek(time_ + 5.0);
      return true;
    case SDLK_PAGEUP:
      seek(time_ - 5.0);
      return true;
    case SDLK_BACKSPACE:
      seek(time_of(0));
      return true;
    default:
      return false;
  }
}

std::string ReplayWorld::keys_help() const {
  return "Space pause  . , step  ] [ speed  PgDn PgUp 5 s  Backspace start";
}

std::vector<std::string> ReplayWorld::panel(const client::PlayoutFrame& frame,
                                            std::optional<std::uint64_t> followed) const {
  const client::Welcome& welcome = recording_.welcome;
  const client::Snapshot& shown = current();
  std::vector<std::string> lines;
  lines.push_back(fmt::format("replay {}  scene '{}'  {:g} ticks/s", name_, welcome.scene_name,
                              welcome.tick_rate));
  lines.push_back(fmt::format("tick {}  shown {:.1f}  hash {:016x}", shown.tick,
                              time_ * welcome.tick_rate, shown.state_hash));
  lines.push_back(fmt::format(
      "{}  {:g}x  ticks {} to {}  snapshot {} of {}", paused_ ? "paused" : "playing", speed_,
      recording_.snapshots.front().snapshot.tick, recording_.snapshots.back().snapshot.tick,
      index_at(time_) + 1, recording_.snapshots.size()));
  lines.push_back(fmt::format("at most {} players; while recording: {} bodies added, {} removed",
                              welcome.max_players, shapes_.joined(), shapes_.left()));
  lines.push_back(shapes_.bodies_line(frame, followed));
  return lines;
}

}  // namespace viewer
