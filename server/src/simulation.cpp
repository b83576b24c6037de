#include "server/simulation.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "server/relay_log.h"
#include "server/rules_tick.h"

namespace server {
namespace {

double pick_tick_rate(double requested, const scene::SceneDef& scene) {
  // 0 means "the scene's"; anything else must itself be a valid rate. A rate near
  // zero (a denormal from a corrupted recording) would make dt = 1 / rate infinite.
  const double rate = requested == 0.0 ? scene.tick_rate : requested;
  if (std::string problem = scene::tick_rate_problem(rate); !problem.empty()) {
    throw std::invalid_argument(problem);
  }
  return rate;
}

}  // namespace

Simulation::Simulation(scene::SceneDef scene, SimulationOptions options,
                       std::shared_ptr<GameRules> rules)
    : scene_(std::move(scene)),
      options_(options),
      tick_rate_(pick_tick_rate(options.tick_rate, scene_)),
      dt_(1.0 / tick_rate_),
      world_(scene::build_world(scene_)),
      rules_(std::move(rules)) {
  if (rules_) {
    set_contact_events(false);
    GameWorld handle(*this);
    rules_->on_create(handle);
    changes_ = {};  // the scene as the rules made it is what every client is welcomed to
  }
}

void Simulation::note_added(phys::BodyId body, const phys::BodyDef& def) {
  changes_.added.push_back(body);
  if (relay_) relay_->added(body, def);
}

void Simulation::note_removed(phys::BodyId body) {
  if (relay_) relay_->removed(body);
  // A body added and removed between two snapshots never needs to be announced.
  auto& added = changes_.added;
  for (auto it = added.begin(); it != added.end(); ++it) {
    if (*it == body) {
      added.erase(it);
      return;
    }
  }
  changes_.removed.push_back(body.packed());
}

void Simulation::end() {
  if (ended_ || !rules_) return;
  ended_ = true;
  rules_tick_ = current_tick_;
  GameWorld handle(*this);
  rules_->on_end(handle);
}

std::optional<phys::BodyId> Simulation::join(ClientId client, std::optional<std::uint32_t> seat) {
  return admit(client, seat).body;
}

Admission Simulation::admit(ClientId client, std::optional<std::uint32_t> seat) {
  Admission admission;
  if (room_.contains(client)) return admission;
  JoinDecision decision;
  if (rules_) {
    rules_tick_ = current_tick_;
    GameWorld handle(*this);
    decision = rules_->on_join(handle, client, seat);
    if (decision.refuse) {
      admission.refused = *decision.refuse;
      return admission;
    }
  }
  phys::BodyDef made;
  const std::optional<phys::BodyId> body =
      decision.body ? room_.join_as(client, *decision.body, world_, &made)
                    : room_.join(client, scene_, world_, seat, &made);
  if (!body) return admission;
  inputs_.emplace(client, ClientInputs{});
  note_added(*body, made);
  if (relay_) relay_->joined(client, *body);
  if (recorder_) recorder_->joined(current_tick_, client, *body, seat);
  admission.body = body;
  if (rules_) {
    GameWorld handle(*this);
    rules_->on_joined(handle, client, *body);
    relay_game_state();
  }
  return admission;
}

bool Simulation::leave(ClientId client) {
  const std::optional<phys::BodyId> body = room_.body_of(client);
  if (!body) return false;
  room_.leave(client, world_);
  if (recorder_) recorder_->left(current_tick_, client);
  inputs_.erase(client);
  last_applied_.erase(client);
  note_removed(*body);
  if (relay_) relay_->left(client);
  if (rules_) {
    rules_tick_ = current_tick_;
    GameWorld handle(*this);
    rules_->on_leave(handle, client);
    relay_game_state();
  }
  return true;
}

InputCheck Simulation::submit_input(ClientId client, std::uint64_t tick, phys::Vec2 acceleration) {
  InputCheck check = check_input(tick, acceleration, current_tick_, options_.max_ticks_ahead,
                                 scene_.max_acceleration);
  if (!check.accepted()) return check;
  const auto it = inputs_.find(client);
  if (it == inputs_.end()) {
    check.verdict = InputVerdict::NotJoined;
    return check;
  }
  it->second.file(check.apply_at, tick, check.acceleration);
  return check;
}

bool Simulation::file_recorded_input(ClientId client, std::uint64_t tick, phys::Vec2 acceleration) {
  const auto it = inputs_.find(client);
  if (it == inputs_.end() || tick <= current_tick_) return false;
  it->second.file(tick, tick, acceleration);
  return true;
}

bool Simulation::all_inputs_present() const {
  const std::uint64_t next = current_tick_ + 1;
  for (const auto& [client, inputs] : inputs_) {
    if (!inputs.has_input_for(next)) return false;
  }
  return true;
}

bool Simulation::any_input_present() const {
  const std::uint64_t next = current_tick_ + 1;
  for (const auto& [client, inputs] : inputs_) {
    if (inputs.has_input_for(next)) return true;
  }
  return false;
}

TickResult Simulation::step_tick() {
  TickResult result;
  result.tick = current_tick_ + 1;
  std::vector<AppliedInput> applied;
  for (auto& [client, inputs] : inputs_) {
    const ClientInputs::Taken taken = inputs.take(result.tick);
    if (!taken.fresh) {
      result.held_over.push_back(client);
      continue;
    }
    // Only the room knows the client's body: nothing else can be moved from here.
    const std::optional<phys::BodyId> body = room_.body_of(client);
    if (body && relay_) {
      // Relayed only when the body's acceleration changes (it is held otherwise).
      const phys::Vec2 before = world_.body(*body)->acceleration;
      world_.set_acceleration(*body, taken.acceleration);
      if (!(world_.body(*body)->acceleration == before)) {
        relay_->applied(result.tick, *body, taken.acceleration);
      }
    } else if (body) {
      world_.set_acceleration(*body, taken.acceleration);
    }
    if (body && rules_) {
      // Listed when it differs from the client's last, as a recording holds inputs,
      // so that a replay hands the rules the same list.
      const auto [last, first] = last_applied_.try_emplace(client, taken.acceleration);
      if (first || !(last->second == taken.acceleration)) {
        last->second = taken.acceleration;
        applied.push_back({client, *body, taken.acceleration});
        if (relay_) relay_->rules_input(result.tick, client, taken.acceleration);
      }
    }
    if (recorder_ && body) recorder_->applied(result.tick, client, taken.acceleration);
  }
  delivering_.clear();
  if (const auto due = game_messages_.find(result.tick); due != game_messages_.end()) {
    for (auto& [client, payloads] : due->second) {
      if (!room_.contains(client)) continue;  // left after sending it
      for (std::string& payload : payloads) {
        if (recorder_) recorder_->game_message(result.tick, client, payload);
        if (relay_) relay_->game_message(result.tick, client, payload);
        delivering_.push_back({client, std::move(payload)});
      }
    }
    game_messages_.erase(due);
  }
  if (rules_) {
    // The rules' changes before the step: after the inputs, in the relay too.
    rules_tick_ = result.tick;
    if (relay_) relay_->begin_rules(RelayLog::RulesPhase::BeforeStep);
    run_rules_before_step(*rules_, *this, result.tick, applied);
    if (relay_) relay_->end_rules();
    delivering_.clear();
  }
  world_.step(dt_);
  current_tick_ = result.tick;
  if (rules_) {
    if (relay_) relay_->begin_rules(RelayLog::RulesPhase::AfterStep);
    run_rules_after_step(*rules_, *this);
    relay_game_state();
    if (relay_) relay_->end_rules();
  }
  if (recorder_) recorder_->stepped(result.tick, world_);
  if (relay_) relay_->stepped(result.tick, world_.state_hash());
  return result;
}

GameMessageVerdict Simulation::submit_game_message(ClientId client, std::uint64_t tick,
                                                   std::string payload) {
  if (!rules_) return GameMessageVerdict::NoGame;
  if (!room_.contains(client)) return GameMessageVerdict::NotJoined;
  if (payload.size() > kMaxGameMessageBytes) return GameMessageVerdict::TooLarge;
  if (tick > current_tick_ + options_.max_ticks_ahead) return GameMessageVerdict::TooFarAhead;
  const bool late = tick <= current_tick_;
  const std::uint64_t at = late ? current_tick_ + 1 : tick;
  std::vector<std::string>& queued = game_messages_[at][client];
  if (queued.size() >= kMaxGameMessagesPerTick) return GameMessageVerdict::TooMany;
  queued.push_back(std::move(payload));
  return late ? GameMessageVerdict::Late : GameMessageVerdict::OnTime;
}

bool Simulation::file_recorded_game_message(ClientId client, std::uint64_t tick,
                                            std::string payload) {
  if (!room_.contains(client) || tick <= current_tick_) return false;
  game_messages_[tick][client].push_back(std::move(payload));
  return true;
}

const ClientInputs* Simulation::inputs_of(ClientId client) const {
  const auto it = inputs_.find(client);
  return it == inputs_.end() ? nullptr : &it->second;
}

void Simulation::relay_game_state() {
  if (!relay_ || world_.game_state() == relayed_game_state_) return;
  relay_->game_state(world_.game_state());
  relayed_game_state_ = world_.game_state();
}

void Simulation::replace_rules(std::shared_ptr<GameRules> rules) {
  rules_ = std::move(rules);
  set_contact_events(world_.contact_events_on());
}

void Simulation::rules_set(phys::BodyId id, std::optional<phys::Vec2> position,
                           std::optional<phys::Vec2> velocity,
                           std::optional<phys::Vec2> acceleration) {
  if (relay_) relay_->set(id, position, velocity, acceleration);
}

GameWorld Simulation::world_handle() {
  rules_tick_ = current_tick_;
  return GameWorld(*this);
}

BodyChanges Simulation::take_changes() { return std::exchange(changes_, BodyChanges{}); }

}  // namespace server
