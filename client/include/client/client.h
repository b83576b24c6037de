#pragma once
// A blocking client for the physics server: connect (TCP, Hello, Welcome), send
// inputs, take snapshots. Every call that waits takes a timeout; nothing blocks
// forever except a write to a server that stopped reading (writes are a few dozen
// bytes, far below the socket's buffer).
//
// The client owns one asio::io_context and runs it only inside its own calls, on
// the caller's thread: one Client must be used from one thread at a time; many
// Clients may be used from many threads.
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "client/connection_state.h"
#include "client/types.h"

namespace physics::wire {
class Snapshot;
}
namespace recording {
class RecordingWriter;
}

namespace client {

struct ClientConfig {
  std::string host = "127.0.0.1";
  std::uint16_t port = 7777;
  std::string name = "physics-client";
  std::string token;  // empty: none sent
  // Sent in Hello; only tests that check version refusal change it.
  std::uint32_t protocol_version = kProtocolVersion;
  // Frames from the server larger than this end the session (ProtocolError).
  std::size_t max_message_bytes = 1u << 20;
  // Snapshots received but not yet taken are kept up to this count; older ones are
  // dropped (and counted) so that a caller that stops taking them cannot make the
  // client grow without bound.
  std::size_t max_buffered_snapshots = 4096;
  // While the caller waits in one of our calls and nothing has been sent for this
  // long, the client sends a Ping, so that a client that only watches is not
  // dropped as idle (the server's idle timeout is 10 s by default). 0 turns it off.
  std::chrono::milliseconds keepalive{2000};
  // How the world is to be sent (Hello.view).
  ViewRequest view;
  // Watch without a body (Hello.spectate): Welcome::spectator, no own body.
  bool spectate = false;
  // Hello.want_world: the Welcome carries the world's state, for a client that runs
  // the world; Encoding::Inputs needs it. That Welcome holds some 300 bytes a body:
  // raise max_message_bytes for worlds over about 3,000 bodies.
  bool want_world = false;
  // Hello.run_rules: this client runs the game's rules itself (a PredictingClient
  // with rules sets it); the relay then carries the game messages, not the rules'
  // changes. Welcome::rules_run_here says whether the server granted it.
  bool run_rules = false;
  // The seat to play in (Hello.seat): with the same seats, a lockstep run gives the
  // same bodies whatever order the clients connect in. Unset: the lowest free seat.
  std::optional<std::uint32_t> seat;
  // Contact events in every snapshot (Hello.contacts): Snapshot::contact_events.
  std::optional<ContactSubscription> contacts;
  // Every sensor's events in the snapshots (Hello.sensor_events):
  // Snapshot::sensor_events.
  bool sensor_events = false;
  // When set, every message received is appended, as it arrived, to this client
  // recording (docs/REPLAY.md, "Client recordings"). Created at the first connect()
  // (which fails with ConnectFailed when it cannot be), kept across reconnects.
  std::string record_path;
};

// Why the client is not (or no longer) connected.
struct ClientError {
  ConnectionState state = ConnectionState::Disconnected;
  // Set when the server said why (an Error message); its code and message.
  std::optional<ServerError> server;
  // Our own description: the socket error, the timeout, what did not parse.
  std::string detail;
  // One line for a person: "refused by server: ERROR_BAD_TOKEN: wrong access token".
  std::string to_string() const;
};

struct ClientStats {
  std::uint64_t bytes_received = 0;  // on the wire, prefixes included
  std::uint64_t bytes_sent = 0;
  std::uint64_t snapshots_received = 0;
  std::uint64_t snapshots_dropped = 0;  // over max_buffered_snapshots
  std::uint64_t errors_received = 0;
  std::uint64_t inputs_sent = 0;
  std::uint64_t records_received = 0;  // body records over all snapshots
  std::uint64_t acks_sent = 0;
  std::uint64_t desyncs = 0;  // snapshots whose view hash differed from ours
  std::uint64_t full_states_received = 0;
};

class Client {
 public:
  explicit Client(ClientConfig config);
  ~Client();
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // Connects, sends Hello and waits for Welcome, all within `timeout`. True when
  // Connected; otherwise state() is a failure and last_error() says why.
  bool connect(std::chrono::milliseconds timeout);

  // The Welcome of the current session (valid once connect() returned true).
  const Welcome& welcome() const { return welcome_; }
  ConnectionState state() const { return state_; }
  const ClientError& last_error() const { return error_; }
  const ClientStats& stats() const { return stats_; }

  // Sends Input{tick, ax, ay, sequence}; the sequence counts up from 1. False when
  // not connected or the write failed (the state then says why).
  bool send_input(std::uint64_t tick, double ax, double ay);
  bool send_ping(std::uint64_t nonce);
  // A message for the game's rules at `tick` (docs/PROTOCOL.md 3.9): at most 256
  // bytes, 4 a tick. Send it before the tick's input, so that a lockstep tick that
  // steps on the input finds it there.
  bool send_game_message(std::uint64_t tick, std::string payload);
  // The game's messages received so far (while waiting for snapshots), oldest first;
  // at most 256 are kept.
  std::vector<GameMessage> take_game_messages() { return std::exchange(game_messages_, {}); }

  // The oldest snapshot not yet taken, waiting up to `timeout` for one to arrive.
  // nullopt on timeout or when the session ended (state() tells which). Taking a
  // snapshot acknowledges it (the Ack goes with the next message or wait): the
  // server sends no more than the view's window of snapshots not yet taken.
  std::optional<Snapshot> next_snapshot(std::chrono::milliseconds timeout);
  // The newest snapshot received, dropping older ones not yet taken; waits up to
  // `timeout` only when none is buffered.
  std::optional<Snapshot> newest_snapshot(std::chrono::milliseconds timeout);
  // Waits for a snapshot satisfying `done`, dropping the ones before it.
  template <class Predicate>
  std::optional<Snapshot> wait_for_snapshot(std::chrono::milliseconds timeout, Predicate done);
  // The next Error message from the server (non-fatal ones keep the session; a
  // fatal one also ends it). Snapshots arriving meanwhile stay buffered.
  std::optional<ServerError> next_error(std::chrono::milliseconds timeout);
  std::optional<Pong> next_pong(std::chrono::milliseconds timeout);
  std::size_t buffered_snapshots() const { return snapshots_.size(); }
  // Asks the server for a full state (the client does so itself when its view hash
  // differs from the server's).
  bool request_full_state();

  // Sends Bye and closes. The state becomes Disconnected.
  void disconnect(const std::string& reason = "bye");

 private:
  struct Io;
  struct Held;
  enum class Wait { Snapshot, Error, Pong };

  bool wait_until(Wait what, std::chrono::milliseconds timeout);
  bool has(Wait what) const;
  void start_read();
  void on_bytes(std::size_t count);
  void handle_frame(const std::string& frame);
  bool send_frame(const std::string& frame);
  void taken(const Snapshot& snapshot);
  bool flush_ack();
  void on_snapshot(const physics::wire::Snapshot& message, std::size_t wire_bytes);
  void fail(ConnectionState state, std::string detail);
  void close_socket();

  ClientConfig config_;
  std::unique_ptr<Io> io_;
  ConnectionState state_ = ConnectionState::Disconnected;
  ClientError error_;
  ClientStats stats_;
  Welcome welcome_;
  std::uint64_t next_sequence_ = 1;
  std::chrono::steady_clock::time_point last_sent_{};
  std::deque<Snapshot> snapshots_;
  std::deque<ServerError> errors_;
  std::deque<Pong> pongs_;
  std::vector<GameMessage> game_messages_;
  std::unique_ptr<Held> held_;
  std::uint64_t ack_due_ = 0;  // the newest tick taken and not yet acknowledged
  bool ack_pending_ = false;
  bool full_state_asked_ = false;
  std::unique_ptr<recording::RecordingWriter> recorder_;
  std::chrono::steady_clock::time_point record_start_{};
};

template <class Predicate>
std::optional<Snapshot> Client::wait_for_snapshot(std::chrono::milliseconds timeout,
                                                  Predicate done) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    auto snapshot = next_snapshot(left.count() > 0 ? left : std::chrono::milliseconds(0));
    if (!snapshot) return std::nullopt;
    if (done(*snapshot)) return snapshot;
  }
}

}  // namespace client
