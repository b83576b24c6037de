#include "snapshot_encoder.h"

#include "wire/framing.h"
#include "wire/messages.h"

namespace server {
namespace {

// ServerMessage.snapshot is field 2, length-delimited: (2 << 3) | 2.
constexpr char kSnapshotFieldTag = 0x12;

void fill_changes(const phys::World& world, const BodyChanges& changes,
                  physics::wire::Snapshot& snapshot) {
  for (const phys::BodyId id : changes.added) {
    if (const std::optional<phys::BodyState> body = world.body(id)) {
      fill_body_shape(*body, *snapshot.add_added());
    }
  }
  for (const std::uint64_t id : changes.removed) snapshot.add_removed(id);
}

}  // namespace

void fill_body_shape(const phys::BodyState& body, physics::wire::BodyShape& shape) {
  shape.set_body_id(body.id.packed());
  if (body.shape == phys::Shape::Circle) {
    shape.set_shape(physics::wire::SHAPE_CIRCLE);
    shape.set_radius(body.radius);
  } else {
    shape.set_shape(physics::wire::SHAPE_BOX);
    shape.mutable_half_extents()->set_x(body.half_extents.x);
    shape.mutable_half_extents()->set_y(body.half_extents.y);
  }
  shape.set_is_static(body.motion == phys::Motion::Static);
  shape.mutable_position()->set_x(body.position.x);
  shape.mutable_position()->set_y(body.position.y);
  shape.set_mass(body.motion == phys::Motion::Static ? 0.0 : body.mass);
  shape.set_restitution(body.restitution);
  shape.mutable_friction()->set_x(body.friction.x);
  shape.mutable_friction()->set_y(body.friction.y);
}

std::shared_ptr<const EncodedSnapshot> encode_snapshot(const phys::World& world, std::uint64_t tick,
                                                       const BodyChanges& changes) {
  auto encoded = std::make_shared<EncodedSnapshot>();
  encoded->tick = tick;
  encoded->state_hash = world.state_hash();

  physics::wire::Snapshot snapshot;
  snapshot.set_tick(tick);
  snapshot.set_state_hash(encoded->state_hash);
  // for_each_body visits in ascending id order, which the protocol promises.
  world.for_each_body([&](const phys::BodyState& body) {
    if (body.motion != phys::Motion::Dynamic) return;
    physics::wire::BodyState* state = snapshot.add_bodies();
    state->set_body_id(body.id.packed());
    state->set_x(body.position.x);
    state->set_y(body.position.y);
    state->set_vx(body.velocity.x);
    state->set_vy(body.velocity.y);
  });
  if (!changes.empty()) {
    physics::wire::Snapshot only_changes;
    fill_changes(world, changes, only_changes);
    encoded->changes = only_changes.SerializeAsString();
    snapshot.MergeFrom(only_changes);
  }
  encoded->shared = snapshot.SerializeAsString();
  return encoded;
}

std::string encode_client_fields(std::uint64_t last_applied_input_tick, bool has_applied_input) {
  physics::wire::Snapshot fields;
  fields.set_last_applied_input_tick(last_applied_input_tick);
  fields.set_has_applied_input(has_applied_input);
  return fields.SerializeAsString();
}

std::string snapshot_frame_header(std::size_t snapshot_bytes) {
  std::string length_of_snapshot;
  wire::append_varint_prefix(snapshot_bytes, length_of_snapshot);
  const std::size_t envelope_bytes = 1 + length_of_snapshot.size() + snapshot_bytes;
  std::string header;
  wire::append_varint_prefix(envelope_bytes, header);
  header.push_back(kSnapshotFieldTag);
  header += length_of_snapshot;
  return header;
}

physics::wire::ServerMessage make_welcome(const Simulation& simulation, std::uint32_t client_id,
                                          phys::BodyId body, bool lockstep) {
  physics::wire::ServerMessage envelope;
  physics::wire::Welcome& welcome = *envelope.mutable_welcome();
  welcome.set_protocol_version(wire::kProtocolVersion);
  welcome.set_client_id(client_id);
  welcome.set_body_id(body.packed());
  welcome.set_tick_rate(simulation.tick_rate());
  welcome.set_current_tick(simulation.current_tick());
  simulation.world().for_each_body(
      [&](const phys::BodyState& state) { fill_body_shape(state, *welcome.add_bodies()); });
  const phys::Vec2 gravity = simulation.world().settings().gravity;
  welcome.mutable_gravity()->set_x(gravity.x);
  welcome.mutable_gravity()->set_y(gravity.y);
  welcome.set_max_acceleration(simulation.scene().max_acceleration);
  welcome.set_lockstep(lockstep);
  welcome.set_max_ticks_ahead(static_cast<std::uint32_t>(
      std::min<std::uint64_t>(simulation.max_ticks_ahead(), UINT32_MAX)));
  welcome.set_scene_name(simulation.scene().name);
  return envelope;
}

}  // namespace server
