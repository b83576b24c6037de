#include "convert.h"

#include <algorithm>
#include <utility>

#include "wire/messages.h"
#include "wire/relay_ticks.h"

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
static_assert(static_cast<int>(ErrorCode::RateLimited) == pb::ERROR_RATE_LIMITED);
static_assert(static_cast<int>(ErrorCode::SpectatorInput) == pb::ERROR_SPECTATOR_INPUT);
static_assert(static_cast<int>(ErrorCode::SeatTaken) == pb::ERROR_SEAT_TAKEN);
static_assert(static_cast<int>(ErrorCode::SeatOutOfRange) == pb::ERROR_SEAT_OUT_OF_RANGE);
static_assert(static_cast<int>(ErrorCode::InputClamped) == pb::ERROR_INPUT_CLAMPED);
static_assert(static_cast<int>(ErrorCode::LockstepStraggler) == pb::ERROR_LOCKSTEP_STRAGGLER);
static_assert(static_cast<int>(ErrorCode::InvalidSubscription) == pb::ERROR_INVALID_SUBSCRIPTION);
static_assert(static_cast<int>(ErrorCode::RefusedByGame) == pb::ERROR_REFUSED_BY_GAME);
static_assert(kProtocolVersion == pb::PROTOCOL_VERSION_CURRENT);
static_assert(static_cast<int>(Encoding::Full) == pb::ENCODING_FULL);
static_assert(static_cast<int>(Encoding::Inputs) == pb::ENCODING_INPUTS);

std::vector<std::uint8_t> bytes(const std::string& text) { return {text.begin(), text.end()}; }

std::vector<Player> players(const google::protobuf::RepeatedPtrField<pb::RelayPlayer>& message) {
  std::vector<Player> out;
  out.reserve(static_cast<std::size_t>(message.size()));
  for (const pb::RelayPlayer& player : message) {
    Player& made = out.emplace_back();
    made.client_id = player.client_id();
    made.body_id = player.body_id();
    if (player.has_rules_input()) made.rules_input = vec(player.rules_input());
  }
  return out;
}

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
  shape.name = message.name();
  shape.is_kinematic = message.is_kinematic();
  shape.is_sensor = message.is_sensor();
  shape.motion = shape.is_static      ? Motion::Static
                 : shape.is_kinematic ? Motion::Kinematic
                                      : Motion::Dynamic;
  shape.velocity = vec(message.velocity());
  shape.acceleration = vec(message.acceleration());
  shape.contact_friction = message.contact_friction();
  if (message.has_category_bits()) shape.filter.category_bits = message.category_bits();
  if (message.has_mask_bits()) shape.filter.mask_bits = message.mask_bits();
  shape.filter.group = message.group();
  return shape;
}

void note_kinematic(std::vector<std::uint64_t>& ids, const std::vector<BodyShape>& added,
                    const std::vector<std::uint64_t>& removed) {
  for (const std::uint64_t id : removed) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    if (it != ids.end() && *it == id) ids.erase(it);
  }
  for (const BodyShape& shape : added) {
    if (shape.motion != Motion::Kinematic) continue;
    const auto it = std::lower_bound(ids.begin(), ids.end(), shape.body_id);
    if (it == ids.end() || *it != shape.body_id) ids.insert(it, shape.body_id);
  }
}

void bodies_held(const wire::Reconstruction& held, const std::vector<std::uint64_t>& kinematic_ids,
                 std::vector<BodyState>& out) {
  out.reserve(held.bodies().size());
  for (const wire::PredictedBody& b : held.bodies()) {
    const bool kinematic = std::binary_search(kinematic_ids.begin(), kinematic_ids.end(), b.id);
    out.push_back(
        {b.id, {b.x, b.y}, {b.vx, b.vy}, kinematic ? Motion::Kinematic : Motion::Dynamic});
  }
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
  welcome.view = from_wire(message.view());
  welcome.max_players = message.max_players();
  welcome.spectator = message.spectator();
  welcome.seat = message.seat();
  welcome.seats = message.seats();
  welcome.world_state = bytes(message.world_state());
  welcome.players = players(message.players());
  welcome.rules_run_here = message.rules_run_here();
  return welcome;
}

Snapshot header_from_wire(const pb::Snapshot& message) {
  Snapshot snapshot;
  snapshot.tick = message.tick();
  snapshot.state_hash = message.state_hash();
  snapshot.added.reserve(static_cast<std::size_t>(message.added_size()));
  for (const auto& shape : message.added()) snapshot.added.push_back(from_wire(shape));
  snapshot.removed.assign(message.removed().begin(), message.removed().end());
  snapshot.full = message.full();
  snapshot.view_hash = message.view_hash();
  snapshot.contact_events.reserve(static_cast<std::size_t>(message.contact_events_size()));
  for (const auto& e : message.contact_events()) {
    snapshot.contact_events.push_back({e.end(), e.tick(), e.body_a(), e.body_b(), vec(e.point()),
                                       vec(e.normal()), e.closing_speed()});
  }
  snapshot.contact_events_dropped = message.contact_events_dropped();
  snapshot.sensor_events.reserve(static_cast<std::size_t>(message.sensor_events_size()));
  for (const auto& e : message.sensor_events()) {
    snapshot.sensor_events.push_back({e.end(), e.tick(), e.sensor(), e.visitor()});
  }
  snapshot.sensor_events_dropped = message.sensor_events_dropped();
  if (message.has_input_margin_us()) snapshot.input_margin_us = message.input_margin_us();
  snapshot.relay.reserve(static_cast<std::size_t>(message.relay_size()));
  // Each relayed tick with its number written in (the server leaves it implied).
  for (int i = 0; i < message.relay_size(); ++i) {
    pb::RelayTick tick = message.relay(i);
    tick.set_tick(wire::relay_tick_number(message, i));
    snapshot.relay.push_back(tick.SerializeAsString());
  }
  snapshot.world_state = bytes(message.world_state());
  snapshot.players = players(message.players());
  return snapshot;
}

View from_wire(const pb::ViewRequest& message) {
  View view;
  view.encoding = static_cast<Encoding>(message.encoding());
  view.position_precision = message.position_precision();
  view.velocity_precision = message.velocity_precision();
  view.position_tolerance = message.position_tolerance();
  view.velocity_tolerance = message.velocity_tolerance();
  view.snapshot_interval = message.snapshot_interval();
  view.window = message.window();
  if (message.has_interest_radius()) view.interest_radius = message.interest_radius();
  if (message.has_interest_rect()) {
    const auto& r = message.interest_rect();
    view.interest_rect = Rect{r.min_x(), r.min_y(), r.max_x(), r.max_y()};
  }
  view.byte_budget = message.byte_budget();
  view.state_hash = message.state_hash();
  view.view_hash_interval = message.view_hash_interval();
  return view;
}

pb::ViewRequest to_wire(const ViewRequest& request) {
  pb::ViewRequest view;
  view.set_encoding(static_cast<pb::Encoding>(request.encoding));
  if (request.position_precision) view.set_position_precision(*request.position_precision);
  if (request.velocity_precision) view.set_velocity_precision(*request.velocity_precision);
  if (request.position_tolerance) view.set_position_tolerance(*request.position_tolerance);
  if (request.velocity_tolerance) view.set_velocity_tolerance(*request.velocity_tolerance);
  if (request.snapshot_interval) view.set_snapshot_interval(*request.snapshot_interval);
  if (request.window) view.set_window(*request.window);
  if (request.interest_radius) view.set_interest_radius(*request.interest_radius);
  if (request.interest_rect) {
    auto* r = view.mutable_interest_rect();
    r->set_min_x(request.interest_rect->min_x);
    r->set_min_y(request.interest_rect->min_y);
    r->set_max_x(request.interest_rect->max_x);
    r->set_max_y(request.interest_rect->max_y);
  }
  if (request.byte_budget) view.set_byte_budget(*request.byte_budget);
  view.set_state_hash(request.state_hash);
  if (request.view_hash_interval) view.set_view_hash_interval(*request.view_hash_interval);
  return view;
}

ServerError from_wire(const pb::Error& message) {
  ServerError error;
  error.raw_code = static_cast<std::uint32_t>(message.code());
  error.code = error.raw_code <= static_cast<std::uint32_t>(ErrorCode::RefusedByGame)
                   ? static_cast<ErrorCode>(error.raw_code)
                   : ErrorCode::Unspecified;
  error.message = message.message();
  error.fatal = message.fatal();
  return error;
}

Pong from_wire(const pb::Pong& message) {
  Pong pong;
  pong.nonce = message.nonce();
  pong.client_time_ns = message.client_time_ns();
  pong.server_tick = message.server_tick();
  return pong;
}

pb::ClientMessage make_hello(const ClientConfig& config) {
  wire::HelloOptions options;
  options.access_token = config.token;
  options.protocol_version = config.protocol_version;
  options.view = to_wire(config.view);
  options.spectate = config.spectate;
  options.want_world = config.want_world;
  options.run_rules = config.run_rules;
  options.sensor_events = config.sensor_events;
  options.seat = config.seat;
  if (config.contacts) {
    pb::ContactSubscription& contacts = options.contacts.emplace();
    contacts.set_all(config.contacts->all);
    for (const std::uint64_t id : config.contacts->body_ids) contacts.add_body_ids(id);
  }
  return wire::make_hello(config.name, std::move(options));
}

}  // namespace client::convert
