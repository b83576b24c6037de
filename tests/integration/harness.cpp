#include "harness.h"

#include <array>

namespace itest {

server::ServerConfig test_config(bool lockstep) {
  // The per-address limits are off, as in every user's test (every client connects
  // from 127.0.0.1); they have tests of their own (attack_test.cpp).
  return physics_testing::test_server_config(lockstep);
}

bool eventually(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(2ms);
  }
  return true;
}

std::uint64_t dropped(const server::ServerStats& stats, server::DropReason reason) {
  const auto it = stats.dropped.find(reason);
  return it == stats.dropped.end() ? 0 : it->second;
}

RawPeer::RawPeer(std::uint16_t port) {
  std::error_code ec;
  socket_.connect({asio::ip::make_address("127.0.0.1"), port}, ec);
  connected_ = !ec;
  if (connected_) socket_.set_option(asio::ip::tcp::no_delay(true), ec);
}

RawPeer::RawPeer(std::uint16_t port, const std::string& local_address) {
  std::error_code ec;
  socket_.open(asio::ip::tcp::v4(), ec);
  if (!ec) socket_.bind({asio::ip::make_address(local_address), 0}, ec);
  if (!ec) socket_.connect({asio::ip::make_address("127.0.0.1"), port}, ec);
  connected_ = !ec;
  if (connected_) socket_.set_option(asio::ip::tcp::no_delay(true), ec);
}

RawPeer::~RawPeer() { close(); }

void RawPeer::close() {
  std::error_code ignored;
  if (socket_.is_open()) socket_.close(ignored);
}

void RawPeer::shutdown_send() {
  std::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
}

void RawPeer::set_receive_buffer(int bytes) {
  std::error_code ignored;
  socket_.set_option(asio::socket_base::receive_buffer_size(bytes), ignored);
}

bool RawPeer::send_bytes(std::string_view bytes) {
  std::error_code ec;
  asio::write(socket_, asio::buffer(bytes.data(), bytes.size()), ec);
  return !ec;
}

bool RawPeer::send(const physics::wire::ClientMessage& message) {
  return send_bytes(wire::encode_frame(message));
}

void RawPeer::start_read() {
  if (reading_ || closed_) return;
  reading_ = true;
  socket_.async_read_some(asio::buffer(buffer_),
                          [this](const std::error_code& error, std::size_t count) {
                            reading_ = false;
                            if (error) {
                              closed_ = true;
                              return;
                            }
                            reader_.feed(std::span<const std::uint8_t>(buffer_.data(), count));
                          });
}

std::optional<physics::wire::ServerMessage> RawPeer::receive(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::string frame;
  for (;;) {
    if (reader_.next(frame) == wire::FrameStatus::Frame) {
      physics::wire::ServerMessage message;
      if (!message.ParseFromString(frame)) return std::nullopt;
      return message;
    }
    if (closed_) return std::nullopt;
    start_read();
    if (context_.stopped()) context_.restart();
    if (context_.run_one_until(deadline) == 0 && std::chrono::steady_clock::now() >= deadline) {
      return std::nullopt;
    }
  }
}

std::optional<physics::wire::Error> RawPeer::receive_error(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return std::nullopt;
    auto message = receive(left);
    if (!message) return std::nullopt;
    if (message->has_error()) return message->error();
  }
}

bool RawPeer::wait_closed(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::string frame;
  while (!closed_) {
    while (reader_.next(frame) == wire::FrameStatus::Frame) {
    }
    start_read();
    if (context_.stopped()) context_.restart();
    if (context_.run_one_until(deadline) == 0 && std::chrono::steady_clock::now() >= deadline) {
      return closed_;
    }
  }
  return true;
}

physics::wire::ClientMessage hello_message(const std::string& name, const std::string& token) {
  physics::wire::ClientMessage message;
  message.mutable_hello()->set_protocol_version(physics::wire::PROTOCOL_VERSION_CURRENT);
  message.mutable_hello()->set_client_name(name);
  if (!token.empty()) message.mutable_hello()->set_access_token(token);
  return message;
}

physics::wire::ClientMessage input_message(std::uint64_t tick, double ax, double ay) {
  physics::wire::ClientMessage message;
  message.mutable_input()->set_tick(tick);
  message.mutable_input()->set_ax(ax);
  message.mutable_input()->set_ay(ay);
  return message;
}

std::string check_server_serves(const RunningServer& server, const std::string& name) {
  client::Client probe(server.client_config(name));
  if (!probe.connect(3s)) return "probe cannot join: " + probe.last_error().to_string();
  const std::uint64_t body = probe.welcome().body_id;
  std::uint64_t last_tick = probe.welcome().current_tick;
  // Inputs keep a lockstep server stepping; a real-time one steps anyway.
  probe.send_input(last_tick + 1, 0.0, 0.0);
  for (int i = 0; i < 3; ++i) {
    auto snapshot = probe.next_snapshot(3s);
    if (!snapshot) return "probe got no snapshot: " + probe.last_error().to_string();
    if (snapshot->tick <= last_tick && i > 0) return "snapshot ticks did not rise";
    if (snapshot->find(body) == nullptr) return "the probe's own body is not in the snapshot";
    last_tick = snapshot->tick;
    probe.send_input(last_tick + 1, 0.0, 0.0);
  }
  probe.disconnect("probe done");
  return "";
}

}  // namespace itest
