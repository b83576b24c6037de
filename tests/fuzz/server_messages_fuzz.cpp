// libFuzzer harness: the byte streams of up to four connections, each cut into
// frames by wire::FrameReader and parsed as ClientMessages, handled the way
// server/src/server.cpp and session.cpp handle them, with ticks stepped in between.
//
// Covered, through the same socket-free classes the server uses: the frame reader
// with the server's limits (max_hello_bytes until a connection joins, then
// max_message_bytes); parse_client_message; the rule that only Hello and Bye may
// come before Hello; Hello (protocol version, token, resolve_view, player and
// spectator joins, the player cap, Simulation::join, SnapshotFeeds::join,
// make_welcome); Input (Simulation::submit_input with every verdict); Ping; Ack
// (SnapshotFeeds::ack); FullStateRequest; Bye and disconnects (Simulation::leave,
// SnapshotFeeds::leave); and each tick as run_one_tick does it (step_tick,
// take_changes, note_added/removed, read_truth, SnapshotFeeds::after_tick), in
// fixed-rate or lockstep mode through LockstepGate with a hand-driven clock. Every
// snapshot produced is checked to parse, as the client would read it.
//
// Not covered: Session and Server::Impl themselves (Asio sockets, write queues and
// their too-slow drops, the timers of the handshake deadline, idle drop and close
// linger, the per-address pending caps, stats and logging); those are exercised by
// tests/integration and tests/server/server_socket_test.cpp over loopback.
#include <google/protobuf/stubs/logging.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>

#include "scene/scene.h"
#include "server/lockstep_gate.h"
#include "server/simulation.h"
#include "snapshot_encoder.h"
#include "snapshot_feeds.h"
#include "truth_frame.h"
#include "wire.pb.h"
#include "wire/framing.h"
#include "wire/messages.h"
#include "wire/view_settings.h"

namespace {

// The server's defaults (server/include/server/server.h), the cap lowered so that
// the fuzzer reaches "server full" with four connections.
constexpr std::size_t kMaxMessageBytes = 1u << 20;
constexpr std::size_t kMaxHelloBytes = 4096;
constexpr std::uint32_t kMaxSnapshotWindow = 64;
constexpr int kMaxPlayers = 2;
constexpr int kMaxSpectators = 1;
constexpr std::size_t kSlots = 4;
const std::string kToken = "fuzz-token";

// A small world: a floor, two boxes, three spawn points.
constexpr const char* kSceneText = R"(
name: "fuzz"
world { gravity { x: 0 y: -10 } tick_rate: 60 steps_per_frame: 2 max_acceleration: 50 }
bodies { box { half_extents { x: 20 y: 0.5 } } is_static: true position { x: 0 y: -0.5 } }
bodies { box { half_extents { x: 0.5 y: 0.5 } } position { x: -3 y: 2 } }
bodies { circle { radius: 0.4 } position { x: 3 y: 1 } restitution: 0.5 }
spawn_points { x: -6 y: 1 }
spawn_points { x: 0 y: 3 }
spawn_points { x: 6 y: 1 }
player { circle { radius: 0.5 } }
)";

const scene::SceneDef& fuzz_scene() {
  static const scene::SceneDef scene = [] {
    scene::SceneResult result = scene::parse_scene_text(kSceneText, "fuzz scene");
    if (!std::holds_alternative<scene::SceneDef>(result)) std::abort();
    return std::get<scene::SceneDef>(std::move(result));
  }();
  return scene;
}

struct Connection {
  std::uint32_t id = 0;
  wire::FrameReader reader{kMaxHelloBytes};
  bool joined = false;
  bool spectator = false;
  bool closed = false;
};

void check_parses(const std::string& bytes) {
  physics::wire::ServerMessage message;
  if (!message.ParseFromString(bytes)) std::abort();
}

class FuzzServer {
 public:
  FuzzServer(bool lockstep, bool with_token)
      : lockstep_(lockstep),
        token_(with_token ? std::optional<std::string>(kToken) : std::nullopt),
        simulation_(fuzz_scene()),
        gate_(std::chrono::milliseconds(250)),
        feeds_(wire::Predictor(simulation_.tick_rate(), simulation_.world().settings().gravity.x,
                               simulation_.world().settings().gravity.y),
               30, lockstep) {}

  ~FuzzServer() {
    for (auto& [slot, connection] : connections_) close(connection);
  }

  void receive(std::size_t slot, std::span<const std::uint8_t> bytes) {
    Connection& connection = open(slot);
    connection.reader.feed(bytes);
    std::string frame;
    while (!connection.closed) {
      const wire::FrameStatus status = connection.reader.next(frame);
      if (status == wire::FrameStatus::NeedMore) return;
      if (status != wire::FrameStatus::Frame) {
        close(connection);  // TooLarge, BadPrefix: a fatal Error in the server
        return;
      }
      physics::wire::ClientMessage message;
      if (!wire::parse_client_message(frame, message)) {
        close(connection);
        return;
      }
      on_message(connection, message);
    }
  }

  void disconnect(std::size_t slot) {
    const auto it = connections_.find(slot);
    if (it != connections_.end()) close(it->second);
  }

  // Fixed-rate: one tick. Lockstep: the clock moves on by `elapsed`, and the gate
  // decides, as try_lockstep does.
  void advance(std::chrono::milliseconds elapsed) {
    if (!lockstep_) {
      run_one_tick();
      return;
    }
    now_ += elapsed;
    for (int guard = 0; guard < 8; ++guard) {
      const server::LockstepGate::Decision decision =
          gate_.decide(simulation_.all_inputs_present(), simulation_.any_input_present(), now_);
      if (decision == server::LockstepGate::Decision::Wait) return;
      run_one_tick();
      gate_.stepped();
    }
  }

 private:
  Connection& open(std::size_t slot) {
    Connection& connection = connections_[slot];
    if (connection.id == 0 || connection.closed) {
      connection = Connection{};
      connection.id = next_id_++;
    }
    return connection;
  }

  void close(Connection& connection) {
    if (connection.closed) return;
    connection.closed = true;
    if (!connection.joined) return;
    if (!connection.spectator) {
      if (!simulation_.leave(connection.id)) std::abort();
      --players_;
    } else {
      --spectators_;
    }
    feeds_.leave(connection.id);
  }

  void on_message(Connection& connection, const physics::wire::ClientMessage& message) {
    using Kind = physics::wire::ClientMessage::KindCase;
    const Kind kind = message.kind_case();
    if (!connection.joined && kind != Kind::kHello && kind != Kind::kBye &&
        kind != Kind::KIND_NOT_SET) {
      close(connection);  // ERROR_UNEXPECTED_MESSAGE
      return;
    }
    switch (kind) {
      case Kind::kHello:
        on_hello(connection, message.hello());
        return;
      case Kind::kInput: {
        if (connection.spectator) return;  // ERROR_SPECTATOR_INPUT, not fatal
        const physics::wire::Input& input = message.input();
        const server::InputCheck check =
            simulation_.submit_input(connection.id, input.tick(), {input.ax(), input.ay()});
        if (check.verdict == server::InputVerdict::NotJoined) std::abort();
        if (check.accepted() && check.apply_at <= simulation_.current_tick()) std::abort();
        if (lockstep_) advance(std::chrono::milliseconds(0));
        return;
      }
      case Kind::kPing: {
        physics::wire::ServerMessage reply;
        reply.mutable_pong()->set_nonce(message.ping().nonce());
        reply.mutable_pong()->set_server_tick(simulation_.current_tick());
        check_parses(reply.SerializeAsString());
        return;
      }
      case Kind::kAck:
        feeds_.ack(connection.id, message.ack().tick());
        return;
      case Kind::kFullStateRequest:
        feeds_.request_full_state(connection.id);
        return;
      case Kind::kGameMessage:
        // No rules here: refused (NoGame), and nothing filed.
        if (simulation_.submit_game_message(connection.id, message.game_message().tick(),
                                            message.game_message().payload()) !=
            server::GameMessageVerdict::NoGame) {
          std::abort();
        }
        return;
      case Kind::kBye:
        close(connection);
        return;
      case Kind::KIND_NOT_SET:
        break;
    }
    close(connection);  // ERROR_MALFORMED
  }

  void on_hello(Connection& connection, const physics::wire::Hello& hello) {
    if (connection.joined || hello.protocol_version() != wire::kProtocolVersion ||
        (token_ && hello.access_token() != *token_)) {
      close(connection);
      return;
    }
    wire::ViewSettings view;
    if (!wire::resolve_view(hello.view(), kMaxSnapshotWindow, view).empty()) {
      close(connection);
      return;
    }
    if (hello.spectate()) {
      if (view.interest == wire::InterestKind::Radius || spectators_ >= kMaxSpectators) {
        close(connection);
        return;
      }
      connection.joined = true;
      connection.spectator = true;
      connection.reader.set_max_message_bytes(kMaxMessageBytes);
      feeds_.join(connection.id, view, std::nullopt);
      ++spectators_;
      return;
    }
    if (players_ >= kMaxPlayers) {
      close(connection);
      return;
    }
    const std::optional<phys::BodyId> body = simulation_.join(connection.id);
    if (!body) {
      close(connection);
      return;
    }
    connection.joined = true;
    connection.reader.set_max_message_bytes(kMaxMessageBytes);
    feeds_.join(connection.id, view, body->packed());
    ++players_;
    const physics::wire::ServerMessage welcome =
        server::make_welcome(simulation_, connection.id, *body, lockstep_, wire::to_wire(view),
                             static_cast<std::uint32_t>(kMaxPlayers));
    check_parses(welcome.SerializeAsString());
  }

  void run_one_tick() {
    const server::TickResult result = simulation_.step_tick();
    const server::BodyChanges changes = simulation_.take_changes();
    for (const phys::BodyId id : changes.added) feeds_.note_added(id.packed());
    for (const std::uint64_t id : changes.removed) feeds_.note_removed(id);
    server::TruthFrame frame = server::read_truth(simulation_.world(), result.tick, &previous_);
    const std::vector<server::FeedOutput> outputs =
        feeds_.after_tick(frame, simulation_.world(), [this](server::FeedClient client) {
          server::ClientFields fields;
          if (const server::ClientInputs* inputs = simulation_.inputs_of(client)) {
            fields.last_applied_input_tick = inputs->last_applied_tick();
            fields.has_applied_input = inputs->has_applied();
          }
          return fields;
        });
    for (const server::FeedOutput& out : outputs) {
      // The session writes the view's shared bytes, then the client's own: together
      // they must parse as one Snapshot.
      physics::wire::Snapshot snapshot;
      const std::string bytes = (out.shared ? *out.shared : std::string()) + out.tail;
      if (!snapshot.ParseFromString(bytes)) std::abort();
      if (feeds_.unacknowledged(out.client) > kMaxSnapshotWindow) std::abort();
    }
    previous_ = std::move(frame);
  }

  bool lockstep_;
  std::optional<std::string> token_;
  server::Simulation simulation_;
  server::LockstepGate gate_;
  server::SnapshotFeeds feeds_;
  server::TruthFrame previous_;
  std::chrono::steady_clock::time_point now_{};
  std::map<std::size_t, Connection> connections_;
  std::uint32_t next_id_ = 1;
  int players_ = 0;
  int spectators_ = 0;
};

}  // namespace

// Input: one byte of options (bit 0 lockstep, bit 1 the server wants a token), then
// records of [control byte][length: 2 bytes, little-endian][length bytes]. Control:
// bits 0-1 the connection, bit 2 it disconnects after these bytes, bits 3-7 how
// many ticks pass after them (lockstep: how many 100 ms steps of the clock).
// libprotobuf logs a line for every string field that is not UTF-8; a fuzzer makes
// millions of those.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  FuzzServer server((data[0] & 1) != 0, (data[0] & 2) != 0);
  std::size_t at = 1;
  while (at + 3 <= size) {
    const std::uint8_t control = data[at];
    std::size_t length = data[at + 1] | (static_cast<std::size_t>(data[at + 2]) << 8);
    at += 3;
    if (length > size - at) length = size - at;
    const std::size_t slot = control & (kSlots - 1);
    server.receive(slot, std::span<const std::uint8_t>(data + at, length));
    at += length;
    if ((control & 4) != 0) server.disconnect(slot);
    for (int i = 0; i < (control >> 3); ++i) server.advance(std::chrono::milliseconds(100));
  }
  return 0;
}
