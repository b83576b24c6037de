#include "live_world.h"

#include <fmt/format.h>

#include <algorithm>

namespace viewer {

LiveWorld::LiveWorld(client::ClientConfig config)
    : client_(std::move(config)), start_(std::chrono::steady_clock::now()) {}

double LiveWorld::seconds(std::chrono::steady_clock::time_point at) const {
  return std::chrono::duration<double>(at - start_).count();
}

double LiveWorld::now() const { return seconds(std::chrono::steady_clock::now()); }

bool LiveWorld::connect(std::chrono::milliseconds timeout) {
  if (!client_.connect(timeout)) return false;
  const client::Welcome& welcome = client_.welcome();
  client::PlayoutSettings settings;
  settings.tick_rate = welcome.tick_rate;
  settings.send_interval = welcome.view.snapshot_interval / welcome.tick_rate;
  const std::string problem = settings.validate();
  if (!problem.empty()) {
    client_.disconnect("bad welcome");
    bad_welcome_ = "the server's Welcome cannot be played out: " + problem;
    return false;
  }
  buffer_.emplace(settings);
  if (!welcome.spectator)
    pacer_ = std::make_unique<client::InputPacer>(client_, client::PacerConfig{});
  shapes_.reset(welcome.bodies);
  traffic_.clear();
  return true;
}

std::optional<client::Snapshot> LiveWorld::next_snapshot(std::chrono::milliseconds wait) {
  if (!pacer_) return client_.next_snapshot(wait);
  const auto hold_still = [this](std::uint64_t tick) {
    messages_.send_queued(client_, tick);
    return client::Vec2{};
  };
  return pacer_->poll(std::chrono::steady_clock::now() + wait, hold_still);
}

std::optional<std::uint64_t> LiveWorld::own_body() const {
  if (!pacer_) return std::nullopt;
  return client_.welcome().body_id;
}

bool LiveWorld::send_game_message(std::string payload) {
  if (!pacer_) return false;
  messages_.queue(std::move(payload));
  return true;
}

std::size_t LiveWorld::pump(std::chrono::milliseconds wait) {
  std::size_t taken = 0;
  while (auto snapshot = next_snapshot(taken == 0 ? wait : std::chrono::milliseconds(0))) {
    shapes_.apply(*snapshot);
    buffer_->push(*snapshot, seconds(snapshot->received_at));
    newest_at_ = snapshot->received_at;
    ++taken;
  }
  messages_.received(client_.take_game_messages());
  const double t = now();
  traffic_.emplace_back(t, client_.stats().bytes_received);
  while (traffic_.size() > 2 && traffic_[1].first < t - 1.0) traffic_.pop_front();
  return taken;
}

const client::PlayoutFrame& LiveWorld::update(double now) {
  if (connected()) pump(std::chrono::milliseconds(1));
  return buffer_->state_at(now);
}

double LiveWorld::kbits_per_second() const {
  if (traffic_.size() < 2) return 0.0;
  const double span = traffic_.back().first - traffic_.front().first;
  if (span <= 0.0) return 0.0;
  return static_cast<double>(traffic_.back().second - traffic_.front().second) * 8.0 / 1000.0 /
         span;
}

double LiveWorld::newest_age() const {
  if (!newest_at_) return 0.0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - *newest_at_).count();
}

std::vector<std::string> LiveWorld::panel(const client::PlayoutFrame& frame,
                                          std::optional<std::uint64_t> followed) const {
  const client::Welcome& welcome = client_.welcome();
  const client::Snapshot* newest = buffer_ ? buffer_->newest() : nullptr;
  std::vector<std::string> lines;
  lines.push_back(fmt::format("scene '{}'  {:g} ticks/s{}", welcome.scene_name, welcome.tick_rate,
                              welcome.lockstep ? "  lockstep" : ""));
  if (newest != nullptr) {
    lines.push_back(fmt::format("tick {}  shown {:.1f}  hash {:016x}", newest->tick,
                                frame.server_time * welcome.tick_rate, newest->state_hash));
  } else {
    lines.push_back(fmt::format("tick {} (no snapshot yet)", welcome.current_tick));
  }
  lines.push_back(fmt::format("{:.1f} kbit/s  newest {:.0f} ms old  delay {:.0f} ms  {}",
                              kbits_per_second(), newest_age() * 1000.0,
                              buffer_ ? buffer_->delay() * 1000.0 : 0.0,
                              client::to_string(frame.status)));
  // The protocol names no body's player and sends no count of players: what the
  // viewer sees is bodies added and removed (a player's body comes and goes with it).
  lines.push_back(fmt::format("at most {} players; since watching: {} bodies added, {} removed",
                              welcome.max_players, shapes_.joined(), shapes_.left()));
  lines.push_back(shapes_.bodies_line(frame, followed));
  if (pacer_) lines.push_back(fmt::format("playing: own body {}", welcome.body_id));
  if (pacer_ || messages_.received_count() > 0) {
    for (std::string& line : messages_.panel_lines()) lines.push_back(std::move(line));
  }
  if (!connected()) lines.push_back("disconnected: " + error());
  return lines;
}

}  // namespace viewer
