#pragma once
// Small helpers for building and reading the envelopes of proto/wire.proto, so that
// both ends (and the tools and tests) spell them the same way.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "wire.pb.h"

namespace wire {

inline constexpr std::uint32_t kProtocolVersion = physics::wire::PROTOCOL_VERSION_CURRENT;

physics::wire::ServerMessage make_error(physics::wire::ErrorCode code, std::string message,
                                        bool fatal);

// Everything a Hello carries besides the client's name (docs/PROTOCOL.md, section 2).
struct HelloOptions {
  std::string access_token;  // empty: none sent
  std::uint32_t protocol_version = kProtocolVersion;
  // Sent only when it asks for something (a field set, or a non-default encoding or
  // state_hash): a view at every default is left out, as an absent view means the
  // same, so a plain Hello is the bytes of docs/PROTOCOL.md's example.
  physics::wire::ViewRequest view;
  bool spectate = false;
  bool want_world = false;            // Hello.want_world (docs/PROTOCOL.md 5.12)
  bool run_rules = false;             // Hello.run_rules
  bool sensor_events = false;         // Hello.sensor_events (docs/PROTOCOL.md 3.7)
  std::optional<std::uint32_t> seat;  // absent: the lowest free seat
  // Sent whenever set, even empty: an empty subscription is a player's own contacts,
  // an absent one is none.
  std::optional<physics::wire::ContactSubscription> contacts;
};

physics::wire::ClientMessage make_hello(std::string client_name, HelloOptions options);
physics::wire::ClientMessage make_hello(std::string client_name, std::string access_token = {},
                                        std::uint32_t protocol_version = kProtocolVersion);
physics::wire::ClientMessage make_input(std::uint64_t tick, double ax, double ay,
                                        std::uint64_t sequence = 0);
physics::wire::ClientMessage make_ack(std::uint64_t tick);
physics::wire::ClientMessage make_ping(std::uint64_t nonce, std::uint64_t client_time_ns = 0);
physics::wire::ClientMessage make_bye(std::string reason);
physics::wire::ClientMessage make_full_state_request();

// Parses one frame's bytes; false when they are not a valid message of that type:
// bytes that do not parse, a proto3 string that is not UTF-8, or more bytes than
// Protobuf can parse at once (INT_MAX). An envelope with no kind set parses (true):
// the caller decides what an empty or newer kind means.
bool parse_client_message(std::string_view bytes, physics::wire::ClientMessage& out);
bool parse_server_message(std::string_view bytes, physics::wire::ServerMessage& out);

// The name of an error code as the .proto spells it ("ERROR_BAD_TOKEN").
std::string_view error_code_name(physics::wire::ErrorCode code);

}  // namespace wire
