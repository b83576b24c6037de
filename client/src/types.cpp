#include "client/types.h"

#include <algorithm>

#include "client/connection_state.h"
#include "wire.pb.h"
#include "wire/messages.h"

namespace client {

Vec2 BodyShape::box_half_size() const {
  return shape == ShapeType::Box ? half_extents : Vec2{radius, radius};
}

const BodyState* Snapshot::find(std::uint64_t body_id) const {
  // Bodies arrive in ascending id (docs/PROTOCOL.md), so a binary search finds one.
  const auto it =
      std::lower_bound(bodies.begin(), bodies.end(), body_id,
                       [](const BodyState& body, std::uint64_t id) { return body.body_id < id; });
  if (it != bodies.end() && it->body_id == body_id) return &*it;
  // Fall back to a scan in case a server does not keep the order.
  const auto scan = std::find_if(bodies.begin(), bodies.end(),
                                 [&](const BodyState& body) { return body.body_id == body_id; });
  return scan == bodies.end() ? nullptr : &*scan;
}

// The client's ErrorCode mirrors the .proto's value for value; the names come from
// the .proto itself (wire::error_code_name), so the two ends never spell one apart.
static_assert(static_cast<int>(ErrorCode::Unspecified) == physics::wire::ERROR_UNSPECIFIED);
static_assert(static_cast<int>(ErrorCode::ProtocolVersion) ==
              physics::wire::ERROR_PROTOCOL_VERSION);
static_assert(static_cast<int>(ErrorCode::TooSlow) == physics::wire::ERROR_TOO_SLOW);
static_assert(static_cast<int>(ErrorCode::NoSpawn) == physics::wire::ERROR_NO_SPAWN);

std::string_view to_string(ErrorCode code) {
  const std::string_view name = wire::error_code_name(static_cast<physics::wire::ErrorCode>(code));
  return name.empty() ? std::string_view("ERROR_UNKNOWN") : name;
}

const char* to_string(ConnectionState state) {
  switch (state) {
    case ConnectionState::ConnectionLost:
      return "connection lost";
    case ConnectionState::ProtocolError:
      return "protocol error";
    case ConnectionState::Refused:
      return "refused by server";
    case ConnectionState::WelcomeTimedOut:
      return "no welcome in time";
    case ConnectionState::ConnectTimedOut:
      return "connect timed out";
    case ConnectionState::ConnectFailed:
      return "connect failed";
    case ConnectionState::Disconnected:
      return "disconnected";
    case ConnectionState::Connecting:
      return "connecting";
    case ConnectionState::AwaitingWelcome:
      return "awaiting welcome";
    case ConnectionState::Connected:
      return "connected";
  }
  return "unknown state";
}

}  // namespace client
