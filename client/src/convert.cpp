#include "convert.h"

#include <algorithm>

namespace client::convert {
namespace {

namespace pb = physics::wire;

Vec2 vec(const pb::Vec2& v) { return {v.x(), v.y()}; }

ShapeType shape_type(pb::ShapeType type) {
  switch (type) {
    case pb::SHAPE_CIRCLE:
      return ShapeType::Circle;
    case pb::SHAPE_BOX:
      return ShapeType::Box;
    default:
      return ShapeType::Unspecified;
  }
}

// Our ErrorCode mirrors the wire enum number for number.
static_assert(static_cast<int>(ErrorCode::NoSpawn) == pb::ERROR_NO_SPAWN);
static_assert(static_cast<int>(ErrorCode::TooSlow) == pb::ERROR_TOO_SLOW);
static_assert(static_cast<int>(ErrorCode::ProtocolVersion) == pb::ERROR_PROTOCOL_VERSION);
static_assert(kProtocolVersion == pb::PROTOCOL_VERSION_CURRENT);

}  // namespace

BodyShape from_wire(const pb::BodyShape& message) {
  BodyShape shape;
  shape.body_id = message.body_id();
  shape.shape = shape_type(message.shape());
  shape.radius = message.radius();
  shape.half_extents = vec(message.half_extents());
  shape.is_static = message.is_static();
  shape.position = vec(message.position());
  shape.mass = message.mass();
  shape.restitution = message.restitution();
  shape.friction = vec(message.friction());
  return shape;
}

Welcome from_wire(const pb::Welcome& message) {
  Welcome welcome;
  welcome.protocol_version = message.protocol_version();
  welcome.client_id = message.client_id();
  welcome.body_id = message.body_id();
  welcome.tick_rate = message.tick_rate();
  welcome.current_tick = message.current_tick();
  welcome.bodies.reserve(static_cast<std::size_t>(message.bodies_size()));
  for (const auto& body : message.bodies()) welcome.bodies.push_back(from_wire(body));
  welcome.gravity = vec(message.gravity());
  welcome.max_acceleration = message.max_acceleration();
  welcome.lockstep = message.lockstep();
  welcome.max_ticks_ahead = message.max_ticks_ahead();
  welcome.scene_name = message.scene_name();
  return welcome;
}

Snapshot from_wire(const pb::Snapshot& message, std::uint64_t own_body) {
  Snapshot snapshot;
  snapshot.tick = message.tick();
  snapshot.state_hash = message.state_hash();
  snapshot.bodies.reserve(static_cast<std::size_t>(message.bodies_size()));
  for (const auto& body : message.bodies()) {
    BodyState state{body.body_id(), {body.x(), body.y()}, {body.vx(), body.vy()}};
    if (state.body_id == own_body) snapshot.own = state;
    snapshot.bodies.push_back(state);
  }
  snapshot.has_applied_input = message.has_applied_input();
  snapshot.last_applied_input_tick = message.last_applied_input_tick();
  snapshot.added.reserve(static_cast<std::size_t>(message.added_size()));
  for (const auto& shape : message.added()) snapshot.added.push_back(from_wire(shape));
  snapshot.removed.assign(message.removed().begin(), message.removed().end());
  return snapshot;
}

ServerError from_wire(const pb::Error& message) {
  ServerError error;
  error.raw_code = static_cast<std::uint32_t>(message.code());
  error.code = error.raw_code <= static_cast<std::uint32_t>(ErrorCode::NoSpawn)
                   ? static_cast<ErrorCode>(error.raw_code)
                   : ErrorCode::Unspecified;
  error.message = message.message();
  error.fatal = message.fatal();
  return error;
}

Pong from_wire(const pb::Pong& message) {
  return {message.nonce(), message.client_time_ns(), message.server_tick()};
}

pb::ClientMessage make_hello(std::uint32_t protocol_version, const std::string& name,
                             const std::string& token) {
  pb::ClientMessage message;
  auto* hello = message.mutable_hello();
  hello->set_protocol_version(protocol_version);
  hello->set_client_name(name);
  if (!token.empty()) hello->set_access_token(token);
  return message;
}

pb::ClientMessage make_input(std::uint64_t tick, double ax, double ay, std::uint64_t sequence) {
  pb::ClientMessage message;
  auto* input = message.mutable_input();
  input->set_tick(tick);
  input->set_ax(ax);
  input->set_ay(ay);
  input->set_sequence(sequence);
  return message;
}

pb::ClientMessage make_ping(std::uint64_t nonce, std::uint64_t client_time_ns) {
  pb::ClientMessage message;
  message.mutable_ping()->set_nonce(nonce);
  message.mutable_ping()->set_client_time_ns(client_time_ns);
  return message;
}

pb::ClientMessage make_bye(const std::string& reason) {
  pb::ClientMessage message;
  message.mutable_bye()->set_reason(reason);
  return message;
}

}  // namespace client::convert
