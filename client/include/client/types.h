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
inline constexpr std::uint32_t kProtocolVersion = 4;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  bool operator==(const Vec2&) const = default;
};

enum class ShapeType : std::uint8_t { Unspecified, Circle, Box };

// How a body moves: never (static), by forces and contacts (dynamic), or by its
// velocity alone, pushing what it meets (kinematic).
enum class Motion : std::uint8_t { Static, Dynamic, Kinematic };

// Which bodies a body collides with (phys::Filter): two bodies of the same nonzero
// group always (positive) or never (negative) collide; otherwise each one's mask
// must hold the other's category.
struct CollisionFilter {
  std::uint32_t category_bits = 0x1;
  std::uint32_t mask_bits = 0xFFFFFFFFu;
  std::int32_t group = 0;
  bool operator==(const CollisionFilter&) const = default;
};

// A body's shape and material, sent once (in Welcome or Snapshot::added): with the
// state the snapshots carry, every field the world's state hash covers.
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
  std::string name;                 // the scene's or the game's name for it; empty: none
  bool is_kinematic = false;        // moved by its velocity alone, infinite mass
  bool is_sensor = false;           // detects overlaps, collides with nothing
  Motion motion = Motion::Dynamic;  // the same as is_static and is_kinematic say
  Vec2 velocity;                    // when sent; a kinematic body keeps it until changed
  Vec2 acceleration;                // when sent (dynamic bodies only)
  double contact_friction = 0.0;
  CollisionFilter filter;

  // Half the size of the axis-aligned box it occupies: a box's half extents, a
  // circle's (radius, radius), as the server sizes bodies.
  Vec2 box_half_size() const;
};

// A moving (dynamic or kinematic) body's state after a tick.
struct BodyState {
  std::uint64_t body_id = 0;
  Vec2 position;
  Vec2 velocity;
  // Its BodyShape's (Welcome or Snapshot::added), kept by the client: Dynamic or
  // Kinematic (a static body never moves, so is never in a snapshot).
  Motion motion = Motion::Dynamic;
  bool operator==(const BodyState&) const = default;
};

// How snapshots describe the bodies (physics.wire.Encoding).
enum class Encoding : std::uint8_t {
  Predicted = 0,  // quantised, only bodies that left the prediction (the default)
  Exact = 1,      // exact doubles, only bodies that changed at all
  Full = 2,       // exact doubles, every moving body in every snapshot
  // No bodies: the inputs the server applied (docs/PROTOCOL.md 5.12), for a client
  // that runs the world (ClientConfig::want_world). This client library reads no
  // bodies from it; the predicting client follows it.
  Inputs = 3,
};

struct Rect {
  double min_x = 0.0;
  double min_y = 0.0;
  double max_x = 0.0;
  double max_y = 0.0;
};

// What a client asks for in Hello.view; a field left empty takes the server's
// default (docs/PROTOCOL.md, section 5.1).
struct ViewRequest {
  Encoding encoding = Encoding::Predicted;
  std::optional<double> position_precision;        // m
  std::optional<double> velocity_precision;        // m/s
  std::optional<double> position_tolerance;        // m
  std::optional<double> velocity_tolerance;        // m/s
  std::optional<std::uint32_t> snapshot_interval;  // every k-th tick
  std::optional<std::uint32_t> window;             // unacknowledged snapshots, at most
  std::optional<double> interest_radius;           // m around the own body
  std::optional<Rect> interest_rect;
  std::optional<std::uint32_t> byte_budget;  // bytes of body records per snapshot
  bool state_hash = false;                   // the world's hash in every snapshot
  // The view hash (and, with Encoding::Inputs, the relay's state hash) every k-th
  // snapshot or tick; empty: the server's default (4).
  std::optional<std::uint32_t> view_hash_interval;
};

// The view in force, as Welcome.view gives it (every field filled in).
struct View {
  Encoding encoding = Encoding::Predicted;
  double position_precision = 0.0;
  double velocity_precision = 0.0;
  double position_tolerance = 0.0;
  double velocity_tolerance = 0.0;
  std::uint32_t snapshot_interval = 1;
  std::uint32_t window = 0;
  std::optional<double> interest_radius;
  std::optional<Rect> interest_rect;
  std::uint32_t byte_budget = 0;
  bool state_hash = false;
  std::uint32_t view_hash_interval = 0;
};

// A player in the world and its body (Welcome::players, Snapshot::players).
struct Player {
  std::uint32_t client_id = 0;
  std::uint64_t body_id = 0;
  // The player's input the game's rules last saw (RelayPlayer.rules_input), if any.
  std::optional<Vec2> rules_input;
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
  View view;
  std::uint32_t max_players = 0;
  bool spectator = false;   // watching: body_id is 0, inputs are refused
  std::uint32_t seat = 0;   // the seat held (docs/PROTOCOL.md, "Seats")
  std::uint32_t seats = 0;  // seats in all
  // With ClientConfig::want_world: the world after current_tick, in the physics
  // core's own format (phys::World::from_bytes). Empty otherwise.
  std::vector<std::uint8_t> world_state;
  // With world_state: the players in that world, ascending client id.
  std::vector<Player> players;
  // ClientConfig::run_rules was granted: the relay carries the game's messages and
  // the rules' inputs, not the rules' changes (docs/PROTOCOL.md, "Running the game's
  // rules").
  bool rules_run_here = false;
};

// A body began (end false) or ended to overlap a sensor, at the end of `tick`'s step
// (Hello.sensor_events, docs/PROTOCOL.md "Sensor events").
struct SensorEvent {
  bool end = false;
  std::uint64_t tick = 0;
  std::uint64_t sensor = 0;  // body ids
  std::uint64_t visitor = 0;
  bool operator==(const SensorEvent&) const = default;
};

// Which contact events to receive (Hello.contacts, docs/PROTOCOL.md "Contact
// events"). A player leaves both empty: its own body's. A spectator sets `all`, or
// lists up to 64 body ids.
struct ContactSubscription {
  bool all = false;
  std::vector<std::uint64_t> body_ids;
};

// Two bodies began (or, with `end`, stopped) touching in tick `tick`.
struct ContactEvent {
  bool end = false;
  std::uint64_t tick = 0;
  std::uint64_t body_a = 0;  // the lower-indexed body
  std::uint64_t body_b = 0;
  Vec2 point;                  // where they touch
  Vec2 normal;                 // unit, from a toward b
  double closing_speed = 0.0;  // m/s along the normal, positive when approaching
  bool operator==(const ContactEvent&) const = default;
};

// The world after tick `tick`, as this client holds it: every moving body in its
// view, reconstructed from what the server sent (exact with Encoding::Exact and
// Encoding::Full; within the view's tolerance with Encoding::Predicted).
struct Snapshot {
  std::uint64_t tick = 0;
  std::uint64_t state_hash = 0;   // the world's, when the view asked for it (else 0)
  std::vector<BodyState> bodies;  // every moving body held, ascending id
  // The own body's state in this snapshot (absent only if the server left it out).
  std::optional<BodyState> own;
  bool has_applied_input = false;
  std::uint64_t last_applied_input_tick = 0;  // valid when has_applied_input
  std::vector<BodyShape> added;
  std::vector<std::uint64_t> removed;
  // The subscribed contact events of the ticks since the previous snapshot, oldest
  // first, and how many were lost over the server's limit.
  std::vector<ContactEvent> contact_events;
  std::uint32_t contact_events_dropped = 0;
  // With ClientConfig::sensor_events: every sensor's events of the ticks since the
  // previous snapshot, oldest first, and how many were lost over the server's limit.
  std::vector<SensorEvent> sensor_events;
  std::uint32_t sensor_events_dropped = 0;
  // How early this client's inputs for the ticks since the previous snapshot arrived
  // at the server, the least of them (negative: late); unset when none named such a
  // tick. InputClock takes it (docs/PROTOCOL.md 3.4).
  std::optional<std::int64_t> input_margin_us;
  std::size_t records = 0;  // bodies this snapshot carried (the rest were predicted)
  bool full = false;        // a full state: the bodies held were rebuilt from it
  // The server's hash of what this client holds (0 on the snapshots that carry none,
  // ViewRequest.view_hash_interval), and whether ours equalled it at the last
  // snapshot that carried one (false: the client has asked for a full state).
  std::uint64_t view_hash = 0;
  bool in_sync = true;
  // Local bookkeeping, not on the wire: when the frame was decoded, and its size
  // on the wire (length prefix included).
  std::chrono::steady_clock::time_point received_at;
  std::size_t wire_bytes = 0;
  // Encoding::Inputs: the ticks stepped since the previous snapshot, oldest first, up
  // to and including `tick`, each a RelayTick (proto/wire.proto) as its wire bytes,
  // for a client that runs the world (physics_relay reads them; this library never
  // steps the world); and, answering a full state request, the world after `tick`
  // (phys::World::from_bytes), empty otherwise.
  std::vector<std::string> relay;
  std::vector<std::uint8_t> world_state;
  std::vector<Player> players;  // with world_state: the players in that world

  const BodyState* find(std::uint64_t body_id) const;
};

// A message from the game running on the server (ServerMessage.game_message): sent
// by its rules while stepping `tick`.
struct GameMessage {
  std::uint64_t tick = 0;
  std::string payload;
};

struct Pong {
  std::uint64_t nonce = 0;
  std::uint64_t client_time_ns = 0;  // the Ping's, in the client's steady clock
  std::uint64_t server_tick = 0;
  // Local bookkeeping, not on the wire: when it was decoded.
  std::chrono::steady_clock::time_point received_at;
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
  InvalidView = 12,
  InvalidAck = 13,
  RateLimited = 14,
  SpectatorInput = 15,
  SeatTaken = 16,
  SeatOutOfRange = 17,
  InputClamped = 18,  // not fatal: said once, at the first clamped input
  LockstepStraggler = 19,
  Internal = 20,             // the server failed handling this client's message; closed
  InvalidSubscription = 21,  // Hello.contacts not allowed as given
  RefusedByGame = 22,        // the game on the server refused the player; message says why
  InvalidGameMessage = 23,   // a GameMessage too large, too many for its tick, or no game
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
