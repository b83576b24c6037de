// The rollback loop: relayed ticks compared with the prediction, confirmed, or
// applied after a restore; the prediction stepped up to the present.
#include "client/prediction_core.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "relay/follow_relay.h"
#include "wire.pb.h"

namespace client {
namespace {

phys::BodyId id_of(std::uint64_t packed) { return phys::BodyId::from_packed(packed); }

phys::Vec2 to_phys(Vec2 v) { return {v.x, v.y}; }

std::string hex(std::uint64_t value) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4)
    text[static_cast<std::size_t>(i)] = kDigits[value & 15];
  return text;
}

// Below this a correction is gone (m): a nanometre is far under a pixel.
constexpr double kNegligibleCorrection = 1e-9;

}  // namespace

PredictionCore::PredictionCore(PredictionConfig config) : config_(config) {}

void PredictionCore::start(phys::World world, std::uint64_t tick, std::uint64_t own_body,
                           double tick_rate, double max_acceleration) {
  dt_ = 1.0 / tick_rate;  // as the server's step: bit for bit the same dt
  max_acceleration_ = max_acceleration > 0.0 ? max_acceleration : 0.0;
  decay_per_tick_ =
      config_.smoothing_time_constant > 0.0 ? std::exp(-dt_ / config_.smoothing_time_constant) : 0;
  own_ = own_body;
  ring_.assign(config_.max_rollback, Slot{});
  inputs_.clear();
  corrections_.clear();
  failed_ = false;
  error_.clear();
  stats_ = {};
  failed_resyncs_ = 0;
  matched_since_resync_ = true;
  shown_tick_ = tick;
  frontier_ = tick;
  target_tick_ = tick;
  begin(std::move(world), tick);
  started_ = true;
}

void PredictionCore::begin(phys::World world, std::uint64_t tick) {
  world_ = std::move(world);
  confirmed_tick_ = tick;
  world_tick_ = tick;
  shown_tick_ = std::max(shown_tick_, tick);
  frontier_ = std::max(frontier_, tick);
  target_tick_ = std::max(target_tick_, tick);
  world_.save_into(confirmed_);
  confirmed_own_acceleration_ = {};
  if (own_ != 0) {
    if (const auto own = world_.body(id_of(own_))) confirmed_own_acceleration_ = own->acceleration;
  }
  awaiting_full_state_ = false;
  request_due_ = false;
}

PredictionCore::Slot& PredictionCore::slot(std::uint64_t tick) {
  return ring_[static_cast<std::size_t>(tick % ring_.size())];
}

void PredictionCore::set_input(std::uint64_t tick, Vec2 acceleration) {
  // The server's input check (server/src/input_buffer.cpp) clamps with the same
  // function and limit, so the clamped value is bit for bit the one it relays.
  const phys::Vec2 a = to_phys(acceleration);
  inputs_[tick] = max_acceleration_ > 0.0 ? phys::clamp_length(a, max_acceleration_) : a;
}

std::optional<phys::Vec2> PredictionCore::own_input_at(std::uint64_t tick) const {
  auto it = inputs_.upper_bound(tick);
  if (it == inputs_.begin()) return std::nullopt;
  return std::prev(it)->second;
}

void PredictionCore::forget_old_inputs() {
  // Only the newest input at or before the confirmed tick can still be held.
  auto it = inputs_.upper_bound(confirmed_tick_);
  if (it == inputs_.begin()) return;
  inputs_.erase(inputs_.begin(), std::prev(it));
}

void PredictionCore::on_snapshot(const Snapshot& snapshot) {
  if (!started_ || failed_) return;
  if (!snapshot.world_state.empty()) apply_world_state(snapshot.tick, snapshot.world_state);
  if (failed_) return;
  // The world is at the confirmed tick: relayed ticks are applied to it directly.
  bool on_confirmed = world_tick_ == confirmed_tick_;
  bool applied = false;
  physics::wire::RelayTick relay;
  for (const std::string& bytes : snapshot.relay) {
    if (awaiting_full_state_) {
      ++stats_.ticks_dropped;
      continue;
    }
    if (!relay.ParseFromString(bytes)) {
      ++stats_.bad_changes;
      ask_full_state("a relayed tick after " + std::to_string(confirmed_tick_) + " does not parse");
      continue;
    }
    if (relay.tick() <= confirmed_tick_) {
      ++stats_.stale_ticks;
      error_ = "relayed tick " + std::to_string(relay.tick()) + " is at or before the confirmed " +
               std::to_string(confirmed_tick_);
      continue;
    }
    if (relay.tick() != confirmed_tick_ + 1) {
      ++stats_.gaps;
      ask_full_state("relayed tick " + std::to_string(relay.tick()) + " after " +
                     std::to_string(confirmed_tick_) + ": the ticks between are missing");
      continue;
    }
    // Every predicted tick confirmed: the next ones were never predicted.
    if (world_tick_ == confirmed_tick_) on_confirmed = true;
    if (!on_confirmed) {
      if (matches(relay)) {
        confirm_predicted(relay);
        continue;
      }
      if (world_tick_ - confirmed_tick_ > config_.max_rollback) {
        ++stats_.deep_rollbacks;
        ask_full_state("a rollback of " + std::to_string(world_tick_ - confirmed_tick_) +
                       " ticks, over the limit of " + std::to_string(config_.max_rollback));
        continue;
      }
      compare_ = positions();
      compare_tick_ = world_tick_;
      world_.restore(confirmed_);
      world_tick_ = confirmed_tick_;
      on_confirmed = true;
      ++stats_.rollbacks;
    }
    applied = apply(relay) || applied;
  }
  if (applied && !awaiting_full_state_) world_.save_into(confirmed_);
  forget_old_inputs();
  predict_to(target_tick_);
  compare_.reset();
  show_up_to_now();
}

bool PredictionCore::matches(const physics::wire::RelayTick& relay) const {
  // Bodies added or removed, or the game's rules at work: nothing predicted them.
  if (relay.changes_size() != 0 || relay.before_step_size() != 0 || relay.after_step_size() != 0) {
    return false;
  }
  const Slot& predicted = ring_[static_cast<std::size_t>(relay.tick() % ring_.size())];
  if (predicted.tick != relay.tick()) return false;
  phys::Vec2 own = confirmed_own_acceleration_;
  for (const physics::wire::RelayInput& input : relay.inputs()) {
    const phys::Vec2 a{input.ax(), input.ay()};
    if (own_ != 0 && input.body_id() == own_) {
      own = a;
      continue;
    }
    // Every other body was predicted to hold its acceleration: the prediction never
    // sets theirs, so the predicted world holds the confirmed one.
    const auto body = world_.body(id_of(input.body_id()));
    if (!body || !(body->acceleration == a)) return false;
  }
  return own_ == 0 || own == predicted.own_acceleration;
}

void PredictionCore::confirm_predicted(const physics::wire::RelayTick& relay) {
  Slot& predicted = slot(relay.tick());
  std::swap(confirmed_, predicted.saved);
  confirmed_tick_ = relay.tick();
  confirmed_own_acceleration_ = predicted.own_acceleration;
  ++stats_.confirmed_ticks;
  ++stats_.matched_ticks;
  if (relay.has_state_hash()) {
    scratch_.restore(confirmed_);
    check_hash(relay.tick(), relay.state_hash(), scratch_.state_hash());
  }
}

bool PredictionCore::apply(const physics::wire::RelayTick& relay) {
  const relay::FollowResult applied = relay::apply_changes_and_inputs(world_, relay);
  if (applied.problem != relay::FollowProblem::None) {
    ++stats_.bad_changes;
    ask_full_state(applied.detail);
    return false;
  }
  confirmed_own_acceleration_ = {};
  if (own_ != 0) {
    if (const auto own = world_.body(id_of(own_))) confirmed_own_acceleration_ = own->acceleration;
  }
  step_world();
  const relay::FollowResult after = relay::apply_after_step(world_, relay);
  if (after.problem != relay::FollowProblem::None) {
    ++stats_.bad_changes;
    ask_full_state(after.detail);
    return false;
  }
  confirmed_tick_ = relay.tick();
  ++stats_.confirmed_ticks;
  if (relay.has_state_hash()) check_hash(relay.tick(), relay.state_hash(), world_.state_hash());
  return true;
}

void PredictionCore::step_world() {
  world_.step(dt_);
  ++world_tick_;
  if (world_tick_ <= frontier_) ++stats_.resimulated_ticks;
  frontier_ = std::max(frontier_, world_tick_);
  if (compare_ && world_tick_ == compare_tick_) {
    add_corrections(*compare_);
    compare_.reset();
  }
}

void PredictionCore::predict_to(std::uint64_t tick) {
  const std::uint64_t limit = confirmed_tick_ + config_.max_rollback;
  const std::uint64_t goal = std::min(tick, limit);
  while (world_tick_ < goal) {
    const std::uint64_t next = world_tick_ + 1;
    Slot& predicted = slot(next);
    predicted.own_acceleration = {};
    if (own_ != 0 && world_.contains(id_of(own_))) {
      if (const auto input = own_input_at(next)) world_.set_acceleration(id_of(own_), *input);
      predicted.own_acceleration = world_.body(id_of(own_))->acceleration;
    }
    if (next > frontier_) ++stats_.predicted_ticks;
    step_world();
    predicted.tick = next;
    world_.save_into(predicted.saved);
  }
}

void PredictionCore::advance_to(std::uint64_t tick) {
  if (!started_ || failed_) return;
  target_tick_ = std::max(target_tick_, tick);
  predict_to(target_tick_);
  if (world_tick_ < target_tick_) ++stats_.barrier_waits;
  show_up_to_now();
}

void PredictionCore::show_up_to_now() {
  if (world_tick_ <= shown_tick_) return;
  decay_corrections(world_tick_ - shown_tick_);
  shown_tick_ = world_tick_;
}

void PredictionCore::check_hash(std::uint64_t tick, std::uint64_t expected, std::uint64_t actual) {
  ++stats_.hashes_checked;
  if (expected == actual) {
    matched_since_resync_ = true;
    failed_resyncs_ = 0;
    return;
  }
  ++stats_.desyncs;
  const std::string what = "state hash after tick " + std::to_string(tick) + ": the server's " +
                           hex(expected) + ", ours " + hex(actual);
  if (!matched_since_resync_ && ++failed_resyncs_ >= config_.max_failed_resyncs) {
    fail(what + "; it never matches, after " + std::to_string(failed_resyncs_) +
         " full states in a row: the server's physics core is not this one");
    return;
  }
  ask_full_state(what);
}

void PredictionCore::ask_full_state(std::string why) {
  error_ = std::move(why);
  if (awaiting_full_state_) return;
  awaiting_full_state_ = true;
  request_due_ = true;
  ++stats_.full_state_requests;
}

bool PredictionCore::take_full_state_request() {
  const bool due = request_due_;
  request_due_ = false;
  return due;
}

void PredictionCore::fail(std::string why) {
  failed_ = true;
  error_ = std::move(why);
}

std::uint64_t PredictionCore::confirmed_hash() {
  scratch_.restore(confirmed_);
  return scratch_.state_hash();
}

phys::World PredictionCore::confirmed_world() const { return phys::World(confirmed_); }

std::vector<PredictionCore::Position> PredictionCore::positions() const {
  std::vector<Position> out;
  out.reserve(world_.dynamic_body_count());
  world_.for_each_body([&](const phys::BodyState& body) {
    if (body.motion != phys::Motion::Static) out.push_back({body.id.packed(), body.position});
  });
  return out;
}

void PredictionCore::add_corrections(const std::vector<Position>& before) {
  for (const Position& old : before) {
    const auto now = world_.body(id_of(old.id));
    if (!now) continue;
    const phys::Vec2 delta = old.position - now->position;
    const double size = phys::length(delta);
    if (size == 0.0) continue;
    stats_.largest_correction = std::max(stats_.largest_correction, size);
    phys::Vec2& shown = corrections_[old.id];
    shown += delta;
    const double total = phys::length(shown);
    if (total > config_.snap_distance) {
      // Too far to glide: shown where it is at once.
      stats_.largest_smoothed_correction = std::max(stats_.largest_smoothed_correction, total);
      corrections_.erase(old.id);
    }
  }
}

void PredictionCore::decay_corrections(std::uint64_t ticks) {
  for (auto it = corrections_.begin(); it != corrections_.end();) {
    if (!world_.contains(id_of(it->first))) {
      it = corrections_.erase(it);
      continue;
    }
    // Past a few hundred ticks any correction is long gone.
    for (std::uint64_t i = 0; i < std::min<std::uint64_t>(ticks, 1000); ++i) {
      const double moved = phys::length(it->second) * (1.0 - decay_per_tick_);
      stats_.largest_smoothed_correction = std::max(stats_.largest_smoothed_correction, moved);
      it->second = it->second * decay_per_tick_;
    }
    if (phys::length(it->second) < kNegligibleCorrection) {
      it = corrections_.erase(it);
    } else {
      ++it;
    }
  }
}

Vec2 PredictionCore::correction(std::uint64_t body_id) const {
  const auto it = corrections_.find(body_id);
  if (it == corrections_.end()) return {};
  return {it->second.x, it->second.y};
}

RenderState PredictionCore::render() const {
  RenderState state;
  state.tick = world_tick_;
  state.bodies.reserve(world_.dynamic_body_count());
  world_.for_each_body([&](const phys::BodyState& body) {
    if (body.motion == phys::Motion::Static) return;
    RenderBody& shown = state.bodies.emplace_back();
    shown.body_id = body.id.packed();
    shown.motion = body.motion == phys::Motion::Kinematic ? Motion::Kinematic : Motion::Dynamic;
    shown.predicted_position = {body.position.x, body.position.y};
    shown.velocity = {body.velocity.x, body.velocity.y};
    const Vec2 offset = correction(shown.body_id);
    shown.position = {body.position.x + offset.x, body.position.y + offset.y};
  });
  return state;
}

}  // namespace client
