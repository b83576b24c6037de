// A Client's calls: connecting (TCP, Hello, Welcome), sending, and waiting for what
// client_receive.cpp takes in.
#include "client/client.h"

#include <algorithm>
#include <asio.hpp>
#include <string>
#include <utility>

#include "client_io.h"
#include "convert.h"
#include "recording/recording_file.h"
#include "wire/framing.h"
#include "wire/messages.h"

namespace client {
namespace {

std::uint64_t now_ns() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
          .count());
}

}  // namespace

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
  game_messages_.clear();
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
  if (!send_frame(wire::encode_frame(convert::make_hello(config_)))) return false;
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
    if (!send_frame(wire::encode_frame(wire::make_ping(0, now_ns())))) return false;
  }
  return state_ == ConnectionState::Connected;
}

bool Client::send_input(std::uint64_t tick, double ax, double ay) {
  if (state_ != ConnectionState::Connected) return false;
  std::string frames;
  if (ack_pending_) {
    frames = wire::encode_frame(wire::make_ack(ack_due_));
    ack_pending_ = false;
    ++stats_.acks_sent;
  }
  frames += wire::encode_frame(wire::make_input(tick, ax, ay, next_sequence_));
  if (!send_frame(frames)) return false;
  ++next_sequence_;
  ++stats_.inputs_sent;
  return true;
}

bool Client::send_game_message(std::uint64_t tick, std::string payload) {
  if (state_ != ConnectionState::Connected) return false;
  physics::wire::ClientMessage message;
  message.mutable_game_message()->set_tick(tick);
  message.mutable_game_message()->set_payload(std::move(payload));
  return send_frame(wire::encode_frame(message));
}

bool Client::send_ping(std::uint64_t nonce) {
  if (state_ != ConnectionState::Connected) return false;
  return send_frame(wire::encode_frame(wire::make_ping(nonce, now_ns())));
}

bool Client::request_full_state() {
  if (state_ != ConnectionState::Connected) return false;
  full_state_asked_ = true;
  return send_frame(wire::encode_frame(wire::make_full_state_request()));
}

void Client::taken(const Snapshot& snapshot) {
  ack_due_ = std::max(ack_due_, snapshot.tick);
  ack_pending_ = true;
}

bool Client::flush_ack() {
  if (!ack_pending_ || state_ != ConnectionState::Connected) return true;
  ack_pending_ = false;
  ++stats_.acks_sent;
  return send_frame(wire::encode_frame(wire::make_ack(ack_due_)));
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
    send_frame(wire::encode_frame(wire::make_bye(reason)));
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
