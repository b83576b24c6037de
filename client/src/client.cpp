#include "client/client.h"

#include <algorithm>
#include <array>
#include <asio.hpp>
#include <utility>

#include "convert.h"
#include "recording/recording_file.h"
#include "wire/framing.h"
#include "wire/predictor.h"
#include "wire/reconstruction.h"

namespace client {
namespace {

using Clock = std::chrono::steady_clock;

// Buffered errors and pongs are few in a healthy session; the bound only stops a
// misbehaving server from growing them without limit.
constexpr std::size_t kMaxBufferedSmallEvents = 256;

std::uint64_t now_ns() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
          .count());
}

// Bytes of the base-128 varint that prefixes a frame of `size` bytes.
std::size_t varint_size(std::size_t size) {
  std::size_t bytes = 1;
  for (; size >= 0x80; size >>= 7) ++bytes;
  return bytes;
}

}  // namespace

struct Client::Io {
  explicit Io(std::size_t max_message_bytes) : reader(max_message_bytes) {}
  asio::io_context context;
  asio::ip::tcp::socket socket{context};
  wire::FrameReader reader;
  std::array<std::uint8_t, 64 * 1024> buffer{};
  bool connect_done = false;
  std::error_code connect_error;

  // Runs handlers on this thread until `done()` or the deadline. False on timeout,
  // or when nothing is left that could make `done()` true.
  template <class Done>
  bool run_until(Clock::time_point deadline, Done done) {
    while (!done()) {
      if (context.stopped()) context.restart();
      if (context.run_one_until(deadline) == 0) {
        if (done()) return true;
        if (Clock::now() >= deadline || context.stopped()) return false;
      }
    }
    return true;
  }
};

// What the client holds between snapshots: the reconstruction the server mirrors,
// and the input fields, which the server sends only when they change.
struct Client::Held {
  wire::Reconstruction reconstruction;
  wire::Predictor predictor;
  wire::Quantum quantum;
  Encoding encoding = Encoding::Predicted;
  std::uint64_t last_applied_input_tick = 0;
  bool has_applied_input = false;
};

std::string ClientError::to_string() const {
  std::string text = client::to_string(state);
  if (server) {
    text += ": ";
    text += client::to_string(server->code);
    if (server->code == ErrorCode::Unspecified && server->raw_code != 0) {
      text += "(" + std::to_string(server->raw_code) + ")";
    }
    if (!server->message.empty()) text += ": " + server->message;
  }
  if (!detail.empty()) text += " (" + detail + ")";
  return text;
}

Client::Client(ClientConfig config) : config_(std::move(config)) {}

Client::~Client() { close_socket(); }

bool Client::connect(std::chrono::milliseconds timeout) {
  close_socket();
  if (!config_.record_path.empty() && !recorder_) {
    physics::recording::Header header;
    physics::recording::ClientRun& run = *header.mutable_client();
    run.set_host(config_.host);
    run.set_port(config_.port);
    run.set_name(config_.name);
    run.set_spectator(config_.spectate);
    std::string problem;
    recorder_ = recording::RecordingWriter::create(config_.record_path, header, &problem);
    if (!recorder_) {
      fail(ConnectionState::ConnectFailed, "cannot record: " + problem);
      return false;
    }
    record_start_ = Clock::now();
  }
  io_ = std::make_unique<Io>(config_.max_message_bytes);
  error_ = {};
  welcome_ = {};
  snapshots_.clear();
  errors_.clear();
  pongs_.clear();
  held_.reset();
  ack_pending_ = false;
  ack_due_ = 0;
  full_state_asked_ = false;
  next_sequence_ = 1;
  state_ = ConnectionState::Connecting;
  const auto deadline = Clock::now() + timeout;

  std::error_code ec;
  asio::ip::tcp::resolver resolver(io_->context);
  const auto endpoints = resolver.resolve(config_.host, std::to_string(config_.port),
                                          asio::ip::tcp::resolver::numeric_service, ec);
  if (ec) {
    fail(ConnectionState::ConnectFailed, "cannot resolve " + config_.host + ": " + ec.message());
    return false;
  }
  asio::async_connect(io_->socket, endpoints,
                      [io = io_.get()](const std::error_code& error, const auto&) {
                        io->connect_done = true;
                        io->connect_error = error;
                      });
  if (!io_->run_until(deadline, [this] { return io_->connect_done; })) {
    fail(ConnectionState::ConnectTimedOut, "no TCP connection to " + config_.host + ":" +
                                               std::to_string(config_.port) + " within " +
                                               std::to_string(timeout.count()) + " ms");
    return false;
  }
  if (io_->connect_error) {
    fail(ConnectionState::ConnectFailed, "cannot connect to " + config_.host + ":" +
                                             std::to_string(config_.port) + ": " +
                                             io_->connect_error.message());
    return false;
  }
  // Snapshots are small and must leave at once: no Nagle delay.
  io_->socket.set_option(asio::ip::tcp::no_delay(true), ec);

  state_ = ConnectionState::AwaitingWelcome;
  physics::wire::ClientMessage hello =
      convert::make_hello(config_.protocol_version, config_.name, config_.token, config_.view,
                          config_.spectate, config_.seat);
  if (config_.contacts) convert::set_contacts(*hello.mutable_hello(), *config_.contacts);
  if (!send_frame(wire::encode_frame(hello))) {
    return false;
  }
  start_read();
  // A lockstep lobby (--lockstep-players) sends Welcome only once every seat is
  // taken: keep the session alive with Pings while waiting, as wait_until does.
  const auto welcomed = [this] { return state_ != ConnectionState::AwaitingWelcome; };
  for (;;) {
    auto until = deadline;
    if (config_.keepalive.count() > 0) until = std::min(until, last_sent_ + config_.keepalive);
    if (io_->run_until(until, welcomed)) break;
    if (Clock::now() >= deadline || io_->context.stopped()) {
      fail(ConnectionState::WelcomeTimedOut,
           "no Welcome within " + std::to_string(timeout.count()) + " ms");
      return false;
    }
    if (!send_frame(wire::encode_frame(convert::make_ping(0, now_ns())))) return false;
  }
  return state_ == ConnectionState::Connected;
}

bool Client::send_input(std::uint64_t tick, double ax, double ay) {
  if (state_ != ConnectionState::Connected) return false;
  std::string frames;
  if (ack_pending_) {
    frames = wire::encode_frame(convert::make_ack(ack_due_));
    ack_pending_ = false;
    ++stats_.acks_sent;
  }
  frames += wire::encode_frame(convert::make_input(tick, ax, ay, next_sequence_));
  if (!send_frame(frames)) return false;
  ++next_sequence_;
  ++stats_.inputs_sent;
  return true;
}

bool Client::send_ping(std::uint64_t nonce) {
  if (state_ != ConnectionState::Connected) return false;
  return send_frame(wire::encode_frame(convert::make_ping(nonce, now_ns())));
}

bool Client::request_full_state() {
  if (state_ != ConnectionState::Connected) return false;
  full_state_asked_ = true;
  return send_frame(wire::encode_frame(convert::make_full_state_request()));
}

void Client::taken(const Snapshot& snapshot) {
  ack_due_ = std::max(ack_due_, snapshot.tick);
  ack_pending_ = true;
}

bool Client::flush_ack() {
  if (!ack_pending_ || state_ != ConnectionState::Connected) return true;
  ack_pending_ = false;
  ++stats_.acks_sent;
  return send_frame(wire::encode_frame(convert::make_ack(ack_due_)));
}

std::optional<Snapshot> Client::next_snapshot(std::chrono::milliseconds timeout) {
  if (!wait_until(Wait::Snapshot, timeout)) return std::nullopt;
  Snapshot snapshot = std::move(snapshots_.front());
  snapshots_.pop_front();
  taken(snapshot);
  return snapshot;
}

std::optional<Snapshot> Client::newest_snapshot(std::chrono::milliseconds timeout) {
  // Take in whatever has already arrived, then keep only the newest.
  if (io_ && state_ == ConnectionState::Connected) {
    if (io_->context.stopped()) io_->context.restart();
    io_->context.poll();
  }
  if (!wait_until(Wait::Snapshot, timeout)) return std::nullopt;
  Snapshot snapshot = std::move(snapshots_.back());
  snapshots_.clear();
  taken(snapshot);
  return snapshot;
}

std::optional<ServerError> Client::next_error(std::chrono::milliseconds timeout) {
  if (!wait_until(Wait::Error, timeout)) return std::nullopt;
  ServerError error = std::move(errors_.front());
  errors_.pop_front();
  return error;
}

std::optional<Pong> Client::next_pong(std::chrono::milliseconds timeout) {
  if (!wait_until(Wait::Pong, timeout)) return std::nullopt;
  Pong pong = pongs_.front();
  pongs_.pop_front();
  return pong;
}

void Client::disconnect(const std::string& reason) {
  if (state_ == ConnectionState::Connected || state_ == ConnectionState::AwaitingWelcome) {
    send_frame(wire::encode_frame(convert::make_bye(reason)));
  }
  close_socket();
  state_ = ConnectionState::Disconnected;
  error_ = {};
}

bool Client::has(Wait what) const {
  switch (what) {
    case Wait::Snapshot:
      return !snapshots_.empty();
    case Wait::Error:
      return !errors_.empty();
    case Wait::Pong:
      return !pongs_.empty();
  }
  return false;
}

bool Client::wait_until(Wait what, std::chrono::milliseconds timeout) {
  if (io_ && !flush_ack()) return has(what);
  if (has(what)) return true;
  if (!io_ || state_ != ConnectionState::Connected) return false;
  const auto deadline = Clock::now() + timeout;
  const auto done = [this, what] { return has(what) || state_ != ConnectionState::Connected; };
  while (!done()) {
    auto until = deadline;
    if (config_.keepalive.count() > 0) until = std::min(until, last_sent_ + config_.keepalive);
    if (!io_->run_until(until, done) && !done()) {
      const auto now = Clock::now();
      if (config_.keepalive.count() > 0 && now >= last_sent_ + config_.keepalive) {
        send_ping(0);  // keepalive; its Pong is kept like any other (bounded)
        continue;
      }
      if (now >= deadline || io_->context.stopped()) break;
    }
  }
  return has(what);
}

void Client::start_read() {
  io_->socket.async_read_some(
      asio::buffer(io_->buffer), [this](const std::error_code& error, std::size_t count) {
        if (error == asio::error::operation_aborted) return;
        if (error) {
          if (state_ == ConnectionState::Connected || state_ == ConnectionState::AwaitingWelcome) {
            const bool closed = error == asio::error::eof;
            fail(ConnectionState::ConnectionLost,
                 closed ? std::string(state_ == ConnectionState::Connected
                                          ? "the server closed the connection"
                                          : "the server closed the connection before Welcome")
                        : error.message());
          }
          return;
        }
        on_bytes(count);
      });
}

void Client::on_bytes(std::size_t count) {
  stats_.bytes_received += count;
  io_->reader.feed(std::span<const std::uint8_t>(io_->buffer.data(), count));
  std::string frame;
  for (;;) {
    switch (io_->reader.next(frame)) {
      case wire::FrameStatus::NeedMore:
        start_read();
        return;
      case wire::FrameStatus::TooLarge:
        fail(ConnectionState::ProtocolError,
             "server frame of " + std::to_string(io_->reader.rejected_length()) +
                 " bytes is over the limit of " + std::to_string(config_.max_message_bytes));
        return;
      case wire::FrameStatus::BadPrefix:
        fail(ConnectionState::ProtocolError, "server sent a bad length prefix");
        return;
      case wire::FrameStatus::Frame:
        handle_frame(frame);
        if (is_failure(state_) || state_ == ConnectionState::Disconnected) return;
        break;
    }
  }
}

void Client::handle_frame(const std::string& frame) {
  if (recorder_) {
    physics::recording::Record record;
    physics::recording::Received& received = *record.mutable_received();
    received.set_micros(static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - record_start_)
            .count()));
    received.set_server_message(frame);
    recorder_->append(record);
  }
  physics::wire::ServerMessage message;
  if (!message.ParseFromString(frame)) {
    fail(ConnectionState::ProtocolError, "server sent a message that does not parse");
    return;
  }
  using Kind = physics::wire::ServerMessage::KindCase;
  switch (message.kind_case()) {
    case Kind::kWelcome:
      if (state_ != ConnectionState::AwaitingWelcome) {
        fail(ConnectionState::ProtocolError, "server sent a second Welcome");
        return;
      }
      welcome_ = convert::from_wire(message.welcome());
      held_ = std::make_unique<Held>();
      held_->predictor =
          wire::Predictor(welcome_.tick_rate, welcome_.gravity.x, welcome_.gravity.y);
      held_->quantum = {welcome_.view.position_precision, welcome_.view.velocity_precision};
      held_->encoding = welcome_.view.encoding;
      state_ = ConnectionState::Connected;
      return;
    case Kind::kSnapshot:
      if (state_ != ConnectionState::Connected) {
        fail(ConnectionState::ProtocolError, "server sent a Snapshot before Welcome");
        return;
      }
      on_snapshot(message.snapshot(), frame.size() + varint_size(frame.size()));
      return;
    case Kind::kError: {
      ServerError error = convert::from_wire(message.error());
      ++stats_.errors_received;
      if (errors_.size() >= kMaxBufferedSmallEvents) errors_.pop_front();
      errors_.push_back(error);
      if (error.fatal) {
        error_.server = error;
        fail(state_ == ConnectionState::AwaitingWelcome ? ConnectionState::Refused
                                                        : ConnectionState::ConnectionLost,
             "");
      }
      return;
    }
    case Kind::kPong:
      if (pongs_.size() >= kMaxBufferedSmallEvents) pongs_.pop_front();
      pongs_.push_back(convert::from_wire(message.pong()));
      return;
    case Kind::KIND_NOT_SET:
      // A kind newer than this client: ignored, as proto3 intends.
      return;
  }
}

void Client::on_snapshot(const physics::wire::Snapshot& message, std::size_t wire_bytes) {
  Held& held = *held_;
  Snapshot snapshot = convert::header_from_wire(message);
  // The input fields come only when they change.
  if (message.has_applied_input()) held.has_applied_input = true;
  if (message.last_applied_input_tick() != 0) {
    held.last_applied_input_tick = message.last_applied_input_tick();
  }
  snapshot.has_applied_input = held.has_applied_input;
  snapshot.last_applied_input_tick = held.last_applied_input_tick;
  if (held.encoding == Encoding::Full) {
    snapshot.bodies.reserve(static_cast<std::size_t>(message.bodies_size()));
    for (const auto& body : message.bodies()) {
      snapshot.bodies.push_back({body.body_id(), {body.x(), body.y()}, {body.vx(), body.vy()}});
    }
    snapshot.records = snapshot.bodies.size();
  } else {
    const std::string problem = held.reconstruction.apply(message, held.predictor, held.quantum);
    if (!problem.empty()) {
      fail(ConnectionState::ProtocolError,
           "server sent a snapshot that does not apply: " + problem);
      return;
    }
    snapshot.records = static_cast<std::size_t>(message.quantized().id_gaps_size() +
                                                message.velocities().id_gaps_size() +
                                                message.exact().id_gaps_size());
    const auto& bodies = held.reconstruction.bodies();
    snapshot.bodies.reserve(bodies.size());
    for (const wire::PredictedBody& b : bodies) {
      snapshot.bodies.push_back({b.id, {b.x, b.y}, {b.vx, b.vy}});
    }
    if (message.full()) {
      full_state_asked_ = false;
      ++stats_.full_states_received;
    }
    snapshot.in_sync = held.reconstruction.hash() == message.view_hash();
    if (!snapshot.in_sync) {
      ++stats_.desyncs;
      if (!full_state_asked_ && !request_full_state()) return;
    }
  }
  if (!welcome_.spectator) {
    if (const BodyState* own = snapshot.find(welcome_.body_id)) snapshot.own = *own;
  }
  snapshot.received_at = Clock::now();
  snapshot.wire_bytes = wire_bytes;
  ++stats_.snapshots_received;
  stats_.records_received += snapshot.records;
  if (snapshots_.size() >= config_.max_buffered_snapshots) {
    snapshots_.pop_front();
    ++stats_.snapshots_dropped;
  }
  snapshots_.push_back(std::move(snapshot));
}

bool Client::send_frame(const std::string& frame) {
  std::error_code ec;
  asio::write(io_->socket, asio::buffer(frame), ec);
  if (ec) {
    fail(ConnectionState::ConnectionLost, "write failed: " + ec.message());
    return false;
  }
  stats_.bytes_sent += frame.size();
  last_sent_ = Clock::now();
  return true;
}

void Client::fail(ConnectionState state, std::string detail) {
  if (is_failure(state_)) return;  // the first reason is the one that counts
  state_ = state;
  error_.state = state;
  error_.detail = std::move(detail);
  close_socket();
}

void Client::close_socket() {
  if (!io_) return;
  std::error_code ignored;
  if (io_->socket.is_open()) {
    io_->socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    io_->socket.close(ignored);
  }
}

}  // namespace client
