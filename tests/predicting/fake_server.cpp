#include "fake_server.h"

#include <stdexcept>
#include <utility>

namespace predicting_test {

FakeServer::FakeServer(int players, std::uint32_t hash_interval)
    : world_(scene::build_world(scene::default_scene())),
      tick_rate_(scene::default_scene().tick_rate),
      max_acceleration_(scene::default_scene().max_acceleration),
      dt_(scene::fixed_dt(scene::default_scene())),
      hash_interval_(hash_interval),
      player_(scene::default_scene().player) {
  const auto& spawns = scene::default_scene().spawn_points;
  for (int i = 0; i < players; ++i) {
    phys::BodyDef def = player_;
    def.position = spawns.at(static_cast<std::size_t>(i) % spawns.size());
    const phys::BodyId id = world_.add_body(def);
    if (!id.is_valid()) throw std::runtime_error("the fake server's player was refused");
    players_.push_back(id.packed());
  }
}

phys::BodyDef FakeServer::player_def(double x) const {
  phys::BodyDef def = player_;
  def.position = {x, 20.0};
  return def;
}

void FakeServer::input(std::uint64_t body, std::uint64_t tick, client::Vec2 a) {
  const phys::Vec2 clamped = phys::clamp_length({a.x, a.y}, max_acceleration_);
  inputs_[body][tick] = {clamped.x, clamped.y};
}

std::uint64_t FakeServer::join_next_tick(const phys::BodyDef& def) {
  joins_.push_back(def);
  // The id the world will give: tried on a copy, so the real add stays in step().
  phys::World probe = copy();
  for (std::uint64_t leaving : leaves_) probe.remove_body(phys::BodyId::from_packed(leaving));
  phys::BodyId id;
  for (const phys::BodyDef& join : joins_) id = probe.add_body(join);
  return id.packed();
}

void FakeServer::leave_next_tick(std::uint64_t body) { leaves_.push_back(body); }

physics::wire::RelayTick FakeServer::step() {
  physics::wire::RelayTick relay;
  relay.set_tick(tick_ + 1);
  // Leaves, then joins, as a server makes them between ticks.
  for (std::uint64_t body : leaves_) {
    world_.remove_body(phys::BodyId::from_packed(body));
    relayed_.erase(body);
    relay.add_changes()->set_removed(body);
  }
  leaves_.clear();
  for (const phys::BodyDef& def : joins_) {
    const phys::BodyId id = world_.add_body(def);
    physics::wire::RelayBody& body = *relay.add_changes()->mutable_added();
    body.set_body_id(id.packed());
    body.set_shape(def.shape == phys::Shape::Circle ? physics::wire::SHAPE_CIRCLE
                                                    : physics::wire::SHAPE_BOX);
    body.set_radius(def.radius);
    body.mutable_half_extents()->set_x(def.half_extents.x);
    body.mutable_half_extents()->set_y(def.half_extents.y);
    body.set_is_static(def.motion == phys::Motion::Static);
    body.mutable_position()->set_x(def.position.x);
    body.mutable_position()->set_y(def.position.y);
    body.mutable_velocity()->set_x(def.velocity.x);
    body.mutable_velocity()->set_y(def.velocity.y);
    body.mutable_acceleration()->set_x(def.acceleration.x);
    body.mutable_acceleration()->set_y(def.acceleration.y);
    body.set_mass(def.mass);
    body.set_restitution(def.restitution);
    body.mutable_friction()->set_x(def.friction.x);
    body.mutable_friction()->set_y(def.friction.y);
    body.set_contact_friction(def.contact_friction);
  }
  joins_.clear();
  // Each body's input for this tick, held from the newest at or before it; relayed
  // only when it differs from the last relayed.
  for (const auto& [body, by_tick] : inputs_) {
    auto it = by_tick.upper_bound(relay.tick());
    if (it == by_tick.begin()) continue;
    const client::Vec2 a = std::prev(it)->second;
    if (!world_.contains(phys::BodyId::from_packed(body))) continue;
    const auto last = relayed_.find(body);
    if (last != relayed_.end() && last->second == a) continue;
    world_.set_acceleration(phys::BodyId::from_packed(body), {a.x, a.y});
    relayed_[body] = a;
    physics::wire::RelayInput& input = *relay.add_inputs();
    input.set_body_id(body);
    input.set_ax(a.x);
    input.set_ay(a.y);
  }
  world_.step(dt_);
  tick_ = relay.tick();
  hashes_[tick_] = world_.state_hash();
  if (hash_interval_ > 0 && tick_ % hash_interval_ == 0) relay.set_state_hash(hashes_[tick_]);
  return relay;
}

client::Snapshot relay_snapshot(const std::vector<physics::wire::RelayTick>& ticks) {
  client::Snapshot snapshot;
  if (!ticks.empty()) snapshot.tick = ticks.back().tick();
  for (const auto& tick : ticks) snapshot.relay.push_back(tick.SerializeAsString());
  return snapshot;
}

}  // namespace predicting_test
