#pragma once
// One connection: a read chain (bytes -> Framing -> parsed ClientMessage -> host) and
// one write queue that nothing else writes around. The Framing is the port's: a
// varint length prefix on the TCP port (tcp_framing.h), binary WebSocket frames on
// the WebSocket port (ws_framing.h); everything else here, limits included, is the
// same for both. Snapshots are never
// dropped here: each builds on the one before (docs/PROTOCOL.md, section 5), and the
// snapshot feeds send a client no more than its window of unacknowledged ones, so
// the queue (and the kernel's buffers) hold at most that. Control messages
// (Welcome, Error, Pong) are bounded too: a client that lets them pile up is too
// slow and is dropped. Everything runs on the server's single io_context thread.
#include <array>
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>

#include "framing.h"
#include "server/server.h"
#include "snapshot_encoder.h"
#include "token_bucket.h"
#include "wire.pb.h"

namespace server {

class Session;

// What a session reports to its owner (the server).
class SessionHost {
 public:
  virtual void on_message(Session& session, physics::wire::ClientMessage& message) = 0;
  // Called once, when the session's end is decided: the Error is queued (or the
  // socket is about to close without one), and the peer may see its end before
  // on_closed. What a peer may do next, such as take a seat again, is settled here.
  virtual void on_closing(Session& /*session*/, DropReason /*reason*/) {}
  // Called once, after the socket is closed.
  virtual void on_closed(Session& session, DropReason reason) = 0;
  virtual void on_bytes(std::size_t sent, std::size_t received) = 0;
  // The session stopped reading for a while: it is over its byte or message rate.
  virtual void on_throttled(Session& /*session*/) {}
  // Handling one of its messages threw; the session closes with ERROR_INTERNAL.
  virtual void on_handler_failed(Session& /*session*/, const char* /*what*/) {}

 protected:
  ~SessionHost() = default;
};

struct SessionLimits {
  std::size_t max_message_bytes = 1u << 20;
  std::size_t max_hello_bytes = 4096;  // the frame limit until the session has joined
  std::chrono::milliseconds handshake_timeout{2000};
  // More queued snapshots than this means the feeds' window bound was broken.
  std::size_t max_queued_snapshots = 257;
  std::size_t max_queued_control = 256;
  // With this many control messages (Pongs, Errors) waiting, the session handles no
  // more of the client's messages until they are written: a burst of Pings waits in
  // the buffers instead of getting the client dropped, and what it makes us hold
  // stays bounded. Below max_queued_control, which only a bug could reach.
  std::size_t pause_reading_at_control = 64;
  // Rate limits on what the peer makes us read and handle (0: unlimited). Over
  // them, reading pauses until the bucket refills.
  double bytes_per_second = 1u << 20;
  double byte_burst = 1u << 20;
  double messages_per_second = 8192;
  double message_burst = 8192;
  std::chrono::milliseconds idle_timeout{10000};
  std::chrono::milliseconds close_linger{1000};
  int socket_send_buffer_bytes = 0;                // 0: the OS default
  double full_state_bytes_per_second = 64 * 1024;  // bursts of twice that
};

class Session : public std::enable_shared_from_this<Session> {
 public:
  using clock = std::chrono::steady_clock;

  // Without a framing, the TCP port's (tcp_framing.h).
  Session(asio::ip::tcp::socket socket, std::uint32_t id, SessionHost& host, SessionLimits limits,
          std::unique_ptr<Framing> framing = nullptr);
  ~Session();

  void start();

  void send(const physics::wire::ServerMessage& message);
  // `shared`: the view's bytes, shared by every client of the view; `tail`: this
  // client's own fields. Both are one Snapshot's encodings, so that their
  // concatenation parses as their merge.
  void send_snapshot(std::shared_ptr<const std::string> shared, std::string tail);
  // Sends a fatal Error, stops reading, closes once it is written (or after
  // close_linger at the latest).
  void close_with_error(physics::wire::ErrorCode code, const std::string& text, DropReason reason);
  // Closes quietly (the peer is gone, or cannot be written to).
  void close_now(DropReason reason);
  // Closes once the framing's goodbye (a WebSocket close frame; nothing on TCP) is
  // written, dropping waiting snapshots and reading nothing more: a Bye, or the
  // peer's own close frame answered. The peer has said it is done, so the socket
  // closes without waiting for its side (RFC 6455 7.1.1: the server closes first).
  void close_when_written(DropReason reason);

  // Enforces idle_timeout and close_linger; the server calls it periodically.
  void check_deadlines(clock::time_point now);

  std::uint32_t id() const { return id_; }
  const std::string& peer() const { return peer_; }
  bool joined() const { return joined_; }
  // Hello.want_world: its Welcome carries the world's state.
  bool wants_world() const { return wants_world_; }
  void set_wants_world(bool wants) { wants_world_ = wants; }
  // Hello.run_rules: it runs the game's rules itself (its relay carries messages).
  bool runs_rules() const { return runs_rules_; }
  void set_runs_rules(bool runs) { runs_rules_ = runs; }
  void set_joined(std::string name) {
    joined_ = true;
    name_ = std::move(name);
    framing_->set_max_message_bytes(limits_.max_message_bytes);
    read_proof_ = clock::now();
  }
  clock::time_point accepted_at() const { return accepted_; }
  // True once any byte has arrived from the peer (a silent socket has sent none).
  bool has_sent_bytes() const { return received_any_; }
  // When the client last proved it reads: an Ack that took snapshots off its
  // window, or a moment with none outstanding. The server drops a joined client
  // whose proof is older than idle_timeout, whatever else it sends.
  clock::time_point read_proof() const { return read_proof_; }
  void note_read_proof(clock::time_point now) { read_proof_ = now; }
  // The full states sent to this client, against their byte budget.
  void spend_full_state(std::size_t bytes) {
    full_state_bucket_.spend(static_cast<double>(bytes), clock::now());
  }
  // Zero when a requested full state fits the budget now; else how long until it does.
  clock::duration full_state_wait(clock::time_point now) { return full_state_bucket_.wait(now); }
  // The peer's address without the port, for the per-address limits.
  const std::string& address() const { return address_; }
  const std::string& name() const { return name_; }
  bool closing() const { return closing_; }
  bool closed() const { return closed_; }
  // Snapshots held: waiting, plus the one being written.
  std::size_t queued_snapshots() const {
    return waiting_snapshots_ + (in_flight_ && in_flight_->snapshot ? 1 : 0);
  }
  std::size_t queued_messages() const { return queue_.size() + (in_flight_ ? 1 : 0); }

 private:
  struct Outgoing {
    std::string bytes;  // a whole frame, or (snapshots) the header built at write time
    std::shared_ptr<const std::string> snapshot;  // null for control messages
    std::string tail;                             // snapshots: this client's own fields
    // What async_write reads from until it completes: the header, the shared
    // bytes, the tail. Lives here, in the heap-held in-flight item, so that it stays
    // put however long the write takes (a local array would die with do_write).
    std::array<asio::const_buffer, 3> buffers;
  };

  void do_read();
  void on_read(std::size_t bytes);
  // Reading paused (rate limits, or control messages waiting): resume when allowed.
  bool must_pause_reading(clock::time_point now);
  void schedule_resume(clock::time_point now);
  void resume();
  std::size_t queued_control() const { return queue_.size() - waiting_snapshots_; }
  void begin_draining();
  void handle_frames();
  // Queues what the framing wrote on its own (a WebSocket's upgrade reply, pongs).
  void flush_output();
  void drop_waiting_snapshots();
  std::string encode(const physics::wire::ServerMessage& message) const;
  void enqueue(Outgoing item);
  void do_write();
  void finish(DropReason reason);
  void announce_closing(DropReason reason);

  asio::ip::tcp::socket socket_;
  std::uint32_t id_;
  SessionHost& host_;
  SessionLimits limits_;
  std::string peer_;
  std::string address_;
  std::string name_;
  std::unique_ptr<Framing> framing_;
  TokenBucket byte_bucket_;
  TokenBucket message_bucket_;
  TokenBucket full_state_bucket_;
  asio::steady_timer resume_timer_;
  bool resume_armed_ = false;
  // Whole frames may still be buffered in framing_: handle them before reading more.
  bool frames_held_ = false;
  std::array<std::uint8_t, 64 * 1024> read_buffer_{};
  // The item being written is taken out of the queue, so that dropping waiting
  // items (erasing from the middle of the deque) can never move it.
  std::unique_ptr<Outgoing> in_flight_;
  std::deque<Outgoing> queue_;  // waiting to be written
  bool reading_ = false;
  bool draining_ = false;              // closing: Error written, FIN sent, discarding input
  bool finish_when_written_ = false;   // closing: close the socket once queue_ is written
  std::size_t waiting_snapshots_ = 0;  // snapshots in queue_
  bool joined_ = false;
  bool closing_ = false;
  bool closed_ = false;
  bool announced_closing_ = false;  // host_.on_closing has been called
  bool wants_world_ = false;
  bool runs_rules_ = false;
  DropReason close_reason_ = DropReason::Disconnected;
  clock::time_point accepted_;
  clock::time_point last_received_;
  clock::time_point read_proof_;
  bool received_any_ = false;
  clock::time_point write_started_;
  clock::time_point close_deadline_;
};

}  // namespace server
