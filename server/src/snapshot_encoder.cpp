#include "snapshot_encoder.h"

#include <bit>

#include "wire/framing.h"
#include "wire/messages.h"

namespace server {
namespace {

// ServerMessage.snapshot is field 2, length-delimited: (2 << 3) | 2.
constexpr char kSnapshotFieldTag = 0x12;

// +0.0 in both: what an absent Vec2 reads as. A -0.0 is sent, since the state hash
// tells it apart.
bool all_bits_zero(phys::Vec2 v) {
  return std::bit_cast<std::uint64_t>(v.x) == 0 && std::bit_cast<std::uint64_t>(v.y) == 0;
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
  shape.set_is_kinematic(body.motion == phys::Motion::Kinematic);
  if (!all_bits_zero(body.velocity)) {
    shape.mutable_velocity()->set_x(body.velocity.x);
    shape.mutable_velocity()->set_y(body.velocity.y);
  }
  if (!all_bits_zero(body.acceleration)) {
    shape.mutable_acceleration()->set_x(body.acceleration.x);
    shape.mutable_acceleration()->set_y(body.acceleration.y);
  }
  shape.set_contact_friction(body.contact_friction);
}

void fill_body_shape(const phys::BodyState& body, const phys::World& world,
                     physics::wire::BodyShape& shape) {
  fill_body_shape(body, shape);
  shape.set_name(std::string(world.name(body.id)));
  shape.set_is_sensor(world.is_sensor(body.id));
  // The filter's fields only where they are not phys::Filter's defaults, as
  // RelayBody sends them: a scene without filters pays nothing for them.
  const phys::Filter filter = world.filter(body.id).value_or(phys::Filter{});
  const phys::Filter defaults;
  if (filter.category_bits != defaults.category_bits) {
    shape.set_category_bits(filter.category_bits);
  }
  if (filter.mask_bits != defaults.mask_bits) shape.set_mask_bits(filter.mask_bits);
  shape.set_group(filter.group);
}

std::string snapshot_frame_header(std::size_t snapshot_bytes) {
  const std::string message_header = snapshot_message_header(snapshot_bytes);
  std::string header;
  wire::append_varint_prefix(message_header.size() + snapshot_bytes, header);
  return header + message_header;
}

std::string snapshot_message_header(std::size_t snapshot_bytes) {
  std::string header(1, kSnapshotFieldTag);
  wire::append_varint_prefix(snapshot_bytes, header);
  return header;
}

physics::wire::ServerMessage make_welcome(const Simulation& simulation, std::uint32_t client_id,
                                          phys::BodyId body, bool lockstep,
                                          const physics::wire::ViewRequest& view,
                                          std::uint32_t max_players) {
  physics::wire::ServerMessage envelope;
  physics::wire::Welcome& welcome = *envelope.mutable_welcome();
  welcome.set_protocol_version(wire::kProtocolVersion);
  welcome.set_client_id(client_id);
  welcome.set_body_id(body.packed());
  welcome.set_tick_rate(simulation.tick_rate());
  welcome.set_current_tick(simulation.current_tick());
  simulation.world().for_each_body([&](const phys::BodyState& state) {
    fill_body_shape(state, simulation.world(), *welcome.add_bodies());
  });
  const phys::Vec2 gravity = simulation.world().settings().gravity;
  welcome.mutable_gravity()->set_x(gravity.x);
  welcome.mutable_gravity()->set_y(gravity.y);
  welcome.set_max_acceleration(simulation.scene().max_acceleration);
  welcome.set_lockstep(lockstep);
  welcome.set_max_ticks_ahead(static_cast<std::uint32_t>(
      std::min<std::uint64_t>(simulation.max_ticks_ahead(), UINT32_MAX)));
  welcome.set_scene_name(simulation.scene().name);
  *welcome.mutable_view() = view;
  welcome.set_max_players(max_players);
  return envelope;
}

}  // namespace server
