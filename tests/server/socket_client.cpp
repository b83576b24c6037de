#include "socket_client.h"

#include "wire/messages.h"

namespace server_test {

SocketClient::SocketClient(std::uint16_t port) : socket_(io_) {
  socket_.connect({asio::ip::make_address("127.0.0.1"), port});
}

void SocketClient::send_raw(const std::string& bytes) {
  std::error_code ec;
  asio::write(socket_, asio::buffer(bytes), ec);
}

void SocketClient::send(const physics::wire::ClientMessage& message) {
  send_raw(wire::encode_frame(message));
}

bool SocketClient::read_some(std::chrono::steady_clock::time_point deadline) {
  if (closed_) return false;
  std::error_code result;
  std::size_t bytes = 0;
  bool done = false;
  socket_.async_read_some(asio::buffer(buffer_), [&](std::error_code ec, std::size_t n) {
    result = ec;
    bytes = n;
    done = true;
  });
  io_.restart();
  io_.run_until(deadline);
  if (!done) {
    socket_.cancel();
    io_.restart();
    io_.run();
    return false;
  }
  if (result) {
    closed_ = true;
    return false;
  }
  reader_.feed(std::span<const std::uint8_t>(buffer_.data(), bytes));
  return true;
}

std::optional<physics::wire::ServerMessage> SocketClient::receive(
    std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::string frame;
  for (;;) {
    const wire::FrameStatus status = reader_.next(frame);
    if (status == wire::FrameStatus::Frame) {
      physics::wire::ServerMessage message;
      if (!wire::parse_server_message(frame, message)) return std::nullopt;
      return message;
    }
    if (status != wire::FrameStatus::NeedMore) return std::nullopt;
    if (!read_some(deadline)) return std::nullopt;
  }
}

bool SocketClient::wait_closed(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!closed_) {
    if (!read_some(deadline) && !closed_) return false;
  }
  return true;
}

std::optional<physics::wire::Welcome> SocketClient::join(const std::string& name) {
  send(full_view_hello(name));
  const auto reply = receive();
  if (!reply || !reply->has_welcome()) return std::nullopt;
  return reply->welcome();
}

physics::wire::ClientMessage full_view_hello(const std::string& name) {
  physics::wire::ClientMessage hello = wire::make_hello(name);
  hello.mutable_hello()->mutable_view()->set_encoding(physics::wire::ENCODING_FULL);
  hello.mutable_hello()->mutable_view()->set_state_hash(true);
  hello.mutable_hello()->mutable_view()->set_window(64);
  return hello;
}

}  // namespace server_test
