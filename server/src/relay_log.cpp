#include "server/relay_log.h"

#include <algorithm>
#include <cassert>
#include <vector>

#include "server/simulation.h"

namespace server {

namespace {
void set_vec2(physics::wire::Vec2& out, phys::Vec2 v) {
  out.set_x(v.x);
  out.set_y(v.y);
}
}  // namespace

RelayLog::RelayLog(std::size_t keep_ticks) : keep_ticks_(std::max<std::size_t>(keep_ticks, 1)) {}

RelayLog::Tick& RelayLog::open_tick() {
  if (!open_started_) {
    open_ = Tick{};
    open_.first_change = next_change_;
    open_started_ = true;
  }
  return open_;
}

physics::wire::RelayChange& RelayLog::next_change_slot() {
  Tick& open = open_tick();
  if (!phase_) {
    ++next_change_;  // numbered: a Welcome may fall between two of them
    return *open.message.add_changes();
  }
  return *phase_ == RulesPhase::BeforeStep ? *open.message.add_before_step()
                                           : *open.message.add_after_step();
}

void RelayLog::added(phys::BodyId id, const phys::BodyDef& def) {
  physics::wire::RelayBody& body = *next_change_slot().mutable_added();
  body.set_body_id(id.packed());
  body.set_shape(def.shape == phys::Shape::Circle ? physics::wire::SHAPE_CIRCLE
                                                  : physics::wire::SHAPE_BOX);
  body.set_radius(def.radius);
  set_vec2(*body.mutable_half_extents(), def.half_extents);
  body.set_is_static(def.motion == phys::Motion::Static);
  set_vec2(*body.mutable_position(), def.position);
  set_vec2(*body.mutable_velocity(), def.velocity);
  set_vec2(*body.mutable_acceleration(), def.acceleration);
  body.set_mass(def.mass);
  body.set_restitution(def.restitution);
  set_vec2(*body.mutable_friction(), def.friction);
  body.set_contact_friction(def.contact_friction);
  body.set_is_kinematic(def.motion == phys::Motion::Kinematic);
  if (!(def.filter == phys::Filter{})) {
    body.set_category_bits(def.filter.category_bits);
    body.set_mask_bits(def.filter.mask_bits);
    body.set_group(def.filter.group);
  }
  body.set_is_sensor(def.is_sensor);
  body.set_name(def.name);
}

void RelayLog::removed(phys::BodyId id) { next_change_slot().set_removed(id.packed()); }

void RelayLog::set(phys::BodyId id, std::optional<phys::Vec2> position,
                   std::optional<phys::Vec2> velocity, std::optional<phys::Vec2> acceleration) {
  physics::wire::RelaySet& set = *next_change_slot().mutable_set();
  set.set_body_id(id.packed());
  if (position) set_vec2(*set.mutable_position(), *position);
  if (velocity) set_vec2(*set.mutable_velocity(), *velocity);
  if (acceleration) set_vec2(*set.mutable_acceleration(), *acceleration);
}

void RelayLog::game_state(const phys::GameState& state) {
  std::vector<std::uint8_t> bytes;
  state.append_bytes(bytes);
  next_change_slot().set_game_state(bytes.data(), bytes.size());
}

void RelayLog::joined(std::uint32_t client, phys::BodyId body) {
  physics::wire::RelayPlayer& player = *open_tick().message.add_joined();
  player.set_client_id(client);
  player.set_body_id(body.packed());
}

void RelayLog::left(std::uint32_t client) { open_tick().message.add_left(client); }

void RelayLog::rules_input(std::uint64_t tick, std::uint32_t client, phys::Vec2 acceleration) {
  Tick& open = open_tick();
  open.message.set_tick(tick);
  physics::wire::RelayRulesInput& input = *open.message.add_rules_inputs();
  input.set_client_id(client);
  input.set_ax(acceleration.x);
  input.set_ay(acceleration.y);
}

void RelayLog::game_message(std::uint64_t tick, std::uint32_t client, const std::string& payload) {
  Tick& open = open_tick();
  open.message.set_tick(tick);
  physics::wire::RelayGameMessage& message = *open.message.add_messages();
  message.set_client_id(client);
  message.set_payload(payload);
}

void RelayLog::applied(std::uint64_t tick, phys::BodyId body, phys::Vec2 acceleration) {
  Tick& open = open_tick();
  open.message.set_tick(tick);
  physics::wire::RelayInput& input = *open.message.add_inputs();
  input.set_body_id(body.packed());
  input.set_ax(acceleration.x);
  input.set_ay(acceleration.y);
}

void RelayLog::stepped(std::uint64_t tick, std::uint64_t state_hash) {
  Tick& open = open_tick();
  open.message.set_tick(tick);
  open.state_hash = state_hash;
  ticks_.push_back(std::move(open));
  open_started_ = false;
  while (ticks_.size() > keep_ticks_) ticks_.pop_front();
}

bool RelayLog::holds_after(std::uint64_t after_tick) const {
  if (ticks_.empty()) return true;  // nothing stepped yet: nothing to send
  if (after_tick >= ticks_.back().message.tick()) return true;
  return ticks_.front().message.tick() <= after_tick + 1;
}

void RelayLog::append(std::uint64_t after_tick, std::uint64_t up_to, std::uint64_t first_change,
                      std::uint32_t hash_interval, Audience audience,
                      physics::wire::Snapshot& out) const {
  assert(holds_after(after_tick));
  if (ticks_.empty() || after_tick >= up_to) return;
  const std::uint64_t oldest = ticks_.front().message.tick();
  for (std::size_t i = after_tick + 1 - oldest; i < ticks_.size(); ++i) {
    const Tick& t = ticks_[i];
    if (t.message.tick() > up_to) break;
    physics::wire::RelayTick& copy = *out.add_relay();
    copy.set_tick(t.message.tick());
    // Changes the client's world already holds (numbered below first_change) are
    // left out; they are always the first ones of their tick.
    for (int c = 0; c < t.message.changes_size(); ++c) {
      if (t.first_change + static_cast<std::uint64_t>(c) < first_change) continue;
      *copy.add_changes() = t.message.changes(c);
    }
    *copy.mutable_inputs() = t.message.inputs();
    *copy.mutable_joined() = t.message.joined();
    *copy.mutable_left() = t.message.left();
    if (audience == Audience::RulesRunners) {
      *copy.mutable_rules_inputs() = t.message.rules_inputs();
      *copy.mutable_messages() = t.message.messages();
    } else {
      *copy.mutable_before_step() = t.message.before_step();
      *copy.mutable_after_step() = t.message.after_step();
    }
    if (hash_interval > 0 && t.message.tick() % hash_interval == 0) {
      copy.set_state_hash(t.state_hash);
    }
  }
}

void write_players(const Simulation& simulation,
                   google::protobuf::RepeatedPtrField<physics::wire::RelayPlayer>& out) {
  for (const auto& [client, body] : simulation.room().members()) {
    physics::wire::RelayPlayer& player = *out.Add();
    player.set_client_id(client);
    player.set_body_id(body.packed());
    if (const std::optional<phys::Vec2> seen = simulation.last_rules_input(client)) {
      set_vec2(*player.mutable_rules_input(), *seen);
    }
  }
}

}  // namespace server
