// The rollback loop: relayed ticks compared with the prediction, confirmed, or
// applied after a restore; the prediction stepped up to the present.
#include "client/prediction_core.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>

#include "prediction_rules.h"
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

}  // namespace

PredictionCore::PredictionCore(PredictionConfig config) : config_(config) {}

void PredictionCore::set_rules(std::shared_ptr<server::GameRules> rules) {
  rules_ = rules ? std::make_shared<PredictionRules>(std::move(rules)) : nullptr;
}

void PredictionCore::start(phys::World world, std::uint64_t tick, std::uint64_t own_body,
                           double tick_rate, double max_acceleration,
                           const std::vector<Player>& players, std::uint32_t own_client) {
  dt_ = 1.0 / tick_rate;  // as the server's step: bit for bit the same dt
  max_acceleration_ = max_acceleration > 0.0 ? max_acceleration : 0.0;
  decay_per_tick_ =
      config_.smoothing_time_constant > 0.0 ? std::exp(-dt_ / config_.smoothing_time_constant) : 0;
  own_ = own_body;
  own_client_ = own_client;
  ring_.assign(config_.max_rollback, Slot{});
  inputs_.clear();
  own_messages_.clear();
  if (rules_ && rules_->wants_contact_events()) world.set_contact_events(true);
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
  reset_players(players);
  started_ = true;
}

void PredictionCore::reset_players(const std::vector<Player>& players) {
  confirmed_own_rules_input_.reset();
  if (!rules_) return;
  rules_->reset(players, own_client_);
  for (const Player& player : players) {
    if (player.client_id == own_client_ && player.rules_input) {
      confirmed_own_rules_input_ = to_phys(*player.rules_input);
    }
  }
}

void PredictionCore::send_message(std::uint64_t tick, std::string payload) {
  // A tick predicted already is not stepped again for it: its confirmation (with the
  // message, or with it filed later) rolls the prediction back.
  if (!rules_ || tick <= world_tick_) return;
  own_messages_[tick].push_back(std::move(payload));
}

std::vector<server::OutgoingGameMessage> PredictionCore::predicted_messages() const {
  std::vector<server::OutgoingGameMessage> out;
  for (std::uint64_t tick = confirmed_tick_ + 1; tick <= world_tick_ && !ring_.empty(); ++tick) {
    const Slot& predicted = ring_[static_cast<std::size_t>(tick % ring_.size())];
    if (predicted.tick != tick) continue;
    out.insert(out.end(), predicted.sent.begin(), predicted.sent.end());
  }
  return out;
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
  own_messages_.erase(own_messages_.begin(), own_messages_.upper_bound(confirmed_tick_));
}

void PredictionCore::on_snapshot(const Snapshot& snapshot) {
  if (!started_ || failed_) return;
  if (!snapshot.world_state.empty()) {
    apply_world_state(snapshot.tick, snapshot.world_state, snapshot.players);
  }
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
  // The rules were handed other inputs or messages (another player's message, the
  // own one filed at another tick): their effects were not predicted.
  if (rules_ && !rules_->same(relay, {predicted.rules_inputs, predicted.rules_messages})) {
    return false;
  }
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
  confirmed_own_rules_input_ = predicted.own_rules_input;
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
  if (rules_) {
    rules_->apply_players(relay);
    if (std::string problem = rules_->check(relay); !problem.empty()) {
      ++stats_.bad_changes;
      ask_full_state(std::move(problem));
      return false;
    }
    const RulesTickInputs in = rules_->confirmed(relay);
    std::vector<server::OutgoingGameMessage> sent_by_server;  // the server sends its own
    if (!step_with_rules(in.inputs, in.messages, sent_by_server)) return false;
    confirmed_own_rules_input_ = rules_->own_input_after(relay, confirmed_own_rules_input_);
  } else {
    step_world();
  }
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

bool PredictionCore::step_with_rules(const std::vector<server::AppliedInput>& inputs,
                                     const std::vector<server::ClientGameMessage>& messages,
                                     std::vector<server::OutgoingGameMessage>& sent) {
  const std::uint64_t tick = world_tick_ + 1;
  try {
    rules_->before_step(world_, tick, dt_, {inputs, messages}, sent);
    step_world();
    rules_->after_step(world_, tick, dt_, sent);
  } catch (const std::exception& thrown) {
    // The server's rules would have failed the tick: this world is not the server's.
    ++stats_.rules_errors;
    ask_full_state("the game's rules threw at tick " + std::to_string(tick) + ": " + thrown.what());
    return false;
  }
  return true;
}

void PredictionCore::predict_to(std::uint64_t tick) {
  const std::uint64_t limit = confirmed_tick_ + config_.max_rollback;
  const std::uint64_t goal = std::min(tick, limit);
  while (world_tick_ < goal) predict_one(world_tick_ + 1);
}

void PredictionCore::predict_one(std::uint64_t next) {
  Slot& predicted = slot(next);
  predicted.own_acceleration = {};
  std::optional<phys::Vec2> fresh;  // the own input sent for this very tick
  if (own_ != 0 && world_.contains(id_of(own_))) {
    if (const auto input = own_input_at(next)) world_.set_acceleration(id_of(own_), *input);
    predicted.own_acceleration = world_.body(id_of(own_))->acceleration;
    if (const auto sent = inputs_.find(next); sent != inputs_.end()) fresh = sent->second;
  }
  if (next > frontier_) ++stats_.predicted_ticks;
  predicted.sent.clear();
  if (rules_) {
    const std::optional<phys::Vec2> seen =
        next == confirmed_tick_ + 1 ? confirmed_own_rules_input_ : slot(next - 1).own_rules_input;
    const auto own_messages = own_messages_.find(next);
    RulesTickInputs in = rules_->predicted(
        fresh, seen, id_of(own_),
        own_messages == own_messages_.end() ? std::vector<std::string>{} : own_messages->second);
    predicted.own_rules_input = in.inputs.empty() ? seen : fresh;
    predicted.rules_inputs = std::move(in.inputs);
    predicted.rules_messages = std::move(in.messages);
    step_with_rules(predicted.rules_inputs, predicted.rules_messages, predicted.sent);
  } else {
    step_world();
  }
  predicted.tick = next;
  world_.save_into(predicted.saved);
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

}  // namespace client
