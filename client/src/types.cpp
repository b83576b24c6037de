#include "client/types.h"

#include <algorithm>

#include "client/connection_state.h"

namespace client {

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

const char* to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::Unspecified:
      return "ERROR_UNSPECIFIED";
    case ErrorCode::ProtocolVersion:
      return "ERROR_PROTOCOL_VERSION";
    case ErrorCode::BadToken:
      return "ERROR_BAD_TOKEN";
    case ErrorCode::ServerFull:
      return "ERROR_SERVER_FULL";
    case ErrorCode::MessageTooLarge:
      return "ERROR_MESSAGE_TOO_LARGE";
    case ErrorCode::Malformed:
      return "ERROR_MALFORMED";
    case ErrorCode::UnexpectedMessage:
      return "ERROR_UNEXPECTED_MESSAGE";
    case ErrorCode::InvalidInput:
      return "ERROR_INVALID_INPUT";
    case ErrorCode::TickTooFarAhead:
      return "ERROR_TICK_TOO_FAR_AHEAD";
    case ErrorCode::TooSlow:
      return "ERROR_TOO_SLOW";
    case ErrorCode::ShuttingDown:
      return "ERROR_SHUTTING_DOWN";
    case ErrorCode::NoSpawn:
      return "ERROR_NO_SPAWN";
  }
  return "ERROR_UNKNOWN";
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
