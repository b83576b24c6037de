#pragma once
// What the client hands out: plain structs converted from the wire messages
// (proto/wire.proto), so that callers never see Protobuf. Field meanings are the
// ones docs/PROTOCOL.md gives for the messages they come from.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace client {

// The protocol version this client speaks (physics.wire.PROTOCOL_VERSION_CURRENT).
inline constexpr std::uint32_t kProtocolVersion = 1;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  bool operator==(const Vec2&) const = default;
};

enum class ShapeType : std::uint8_t { Unspecified, Circle, Box };

// A body's shape and material, sent once (in Welcome or Snapshot::added).
struct BodyShape {
  std::uint64_t body_id = 0;
  ShapeType shape = ShapeType::Unspecified;
  double radius = 0.0;
  Vec2 half_extents;
  bool is_static = false;
  Vec2 position;  // where it was when sent; static bodies stay there
  double mass = 0.0;
  double restitution = 0.0;
  Vec2 friction;
};

// A dynamic body's state after a tick.
struct BodyState {
  std::uint64_t body_id = 0;
  Vec2 position;
  Vec2 velocity;
  bool operator==(const BodyState&) const = default;
};

struct Welcome {
  std::uint32_t protocol_version = 0;
  std::uint32_t client_id = 0;
  std::uint64_t body_id = 0;       // the body this client controls
  double tick_rate = 0.0;          // ticks per second
  std::uint64_t current_tick = 0;  // the last tick stepped when we joined
  std::vector<BodyShape> bodies;
  Vec2 gravity;
  double max_acceleration = 0.0;
  bool lockstep = false;
  std::uint32_t max_ticks_ahead = 0;
  std::string scene_name;
};

// The world after tick `tick`.
struct Snapshot {
  std::uint64_t tick = 0;
  std::uint64_t state_hash = 0;
  std::vector<BodyState> bodies;  // every dynamic body, ascending id
  // The own body's state in this snapshot (absent only if the server left it out).
  std::optional<BodyState> own;
  bool has_applied_input = false;
  std::uint64_t last_applied_input_tick = 0;  // valid when has_applied_input
  std::vector<BodyShape> added;
  std::vector<std::uint64_t> removed;
  // Local bookkeeping, not on the wire: when the frame was decoded, and its size
  // on the wire (length prefix included).
  std::chrono::steady_clock::time_point received_at;
  std::size_t wire_bytes = 0;

  const BodyState* find(std::uint64_t body_id) const;
};

struct Pong {
  std::uint64_t nonce = 0;
  std::uint64_t client_time_ns = 0;
  std::uint64_t server_tick = 0;
};

// The server's error codes; the numbers are physics.wire.ErrorCode's.
enum class ErrorCode : std::uint32_t {
  Unspecified = 0,
  ProtocolVersion = 1,
  BadToken = 2,
  ServerFull = 3,
  MessageTooLarge = 4,
  Malformed = 5,
  UnexpectedMessage = 6,
  InvalidInput = 7,
  TickTooFarAhead = 8,
  TooSlow = 9,
  ShuttingDown = 10,
  NoSpawn = 11,
};

std::string_view to_string(ErrorCode code);

// An Error message as the server sent it.
struct ServerError {
  ErrorCode code = ErrorCode::Unspecified;
  std::uint32_t raw_code = 0;  // the number on the wire (codes newer than ours too)
  std::string message;
  bool fatal = false;
};

}  // namespace client
