#include "server/simulation.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "server/relay_log.h"

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

Simulation::Simulation(scene::SceneDef scene, SimulationOptions options)
    : scene_(std::move(scene)),
      options_(options),
      tick_rate_(pick_tick_rate(options.tick_rate, scene_)),
      dt_(1.0 / tick_rate_),
      world_(scene::build_world(scene_)) {}

std::optional<phys::BodyId> Simulation::join(ClientId client, std::optional<std::uint32_t> seat) {
  phys::BodyDef made;
  const std::optional<phys::BodyId> body = room_.join(client, scene_, world_, seat, &made);
  if (body) {
    if (relay_) relay_->added(*body, made);
    inputs_.emplace(client, ClientInputs{});
    changes_.added.push_back(*body);
    if (recorder_) recorder_->joined(current_tick_, client, *body, seat);
  }
  return body;
}

bool Simulation::leave(ClientId client) {
  const std::optional<phys::BodyId> body = room_.body_of(client);
  if (!body) return false;
  room_.leave(client, world_);
  if (relay_) relay_->removed(*body);
  if (recorder_) recorder_->left(current_tick_, client);
  inputs_.erase(client);
  // A body added and removed between two snapshots never needs to be announced.
  auto& added = changes_.added;
  bool was_announced = true;
  for (auto it = added.begin(); it != added.end(); ++it) {
    if (*it == *body) {
      added.erase(it);
      was_announced = false;
      break;
    }
  }
  if (was_announced) changes_.removed.push_back(body->packed());
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
    if (recorder_ && body) recorder_->applied(result.tick, client, taken.acceleration);
  }
  world_.step(dt_);
  if (recorder_) recorder_->stepped(result.tick, world_);
  if (relay_) relay_->stepped(result.tick, world_.state_hash());
  current_tick_ = result.tick;
  return result;
}

const ClientInputs* Simulation::inputs_of(ClientId client) const {
  const auto it = inputs_.find(client);
  return it == inputs_.end() ? nullptr : &it->second;
}

BodyChanges Simulation::take_changes() { return std::exchange(changes_, BodyChanges{}); }

}  // namespace server
