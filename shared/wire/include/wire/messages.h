#pragma once
// Small helpers for building and reading the envelopes of proto/wire.proto, so that
// both ends spell them the same way.
#include <cstdint>
#include <string>
#include <string_view>

#include "wire.pb.h"

namespace wire {

inline constexpr std::uint32_t kProtocolVersion = physics::wire::PROTOCOL_VERSION_CURRENT;

physics::wire::ServerMessage make_error(physics::wire::ErrorCode code, std::string message,
                                        bool fatal);
physics::wire::ClientMessage make_hello(std::string client_name, std::string access_token = {},
                                        std::uint32_t protocol_version = kProtocolVersion);
physics::wire::ClientMessage make_input(std::uint64_t tick, double ax, double ay,
                                        std::uint64_t sequence = 0);

// Parses one frame's bytes; false when they are not a valid message of that type.
bool parse_client_message(std::string_view bytes, physics::wire::ClientMessage& out);
bool parse_server_message(std::string_view bytes, physics::wire::ServerMessage& out);

// The name of an error code as the .proto spells it ("ERROR_BAD_TOKEN").
std::string_view error_code_name(physics::wire::ErrorCode code);

}  // namespace wire
