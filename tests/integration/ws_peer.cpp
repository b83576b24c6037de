#include "ws_peer.h"

namespace itest {

WsPeer::WsPeer(std::uint16_t port, const std::string& path)
    : framing_("ws://127.0.0.1:" + std::to_string(port) + path) {
  std::error_code ec;
  socket_.connect({asio::ip::make_address("127.0.0.1"), port}, ec);
  connected_ = !ec;
  if (connected_) socket_.set_option(asio::ip::tcp::no_delay(true), ec);
}

WsPeer::~WsPeer() {
  std::error_code ignored;
  if (socket_.is_open()) socket_.close(ignored);
}

bool WsPeer::send_raw(std::string_view bytes) {
  std::error_code ec;
  asio::write(socket_, asio::buffer(bytes.data(), bytes.size()), ec);
  return !ec;
}

bool WsPeer::flush() {
  const std::string bytes = framing_.take_output();
  return bytes.empty() || send_raw(bytes);
}

void WsPeer::start_read() {
  if (reading_ || closed_) return;
  reading_ = true;
  socket_.async_read_some(asio::buffer(buffer_),
                          [this](const std::error_code& error, std::size_t count) {
                            reading_ = false;
                            if (error) {
                              closed_ = true;
                              return;
                            }
                            raw_.append(buffer_.data(), count);
                            framing_.feed(buffer_.data(), count);
                          });
}

template <class Done>
bool WsPeer::pump(Done&& done, std::chrono::steady_clock::time_point deadline) {
  for (;;) {
    if (done()) return true;
    // Replies the library owes (pongs, its close acknowledgement).
    flush();
    if (closed_) return done();
    start_read();
    if (context_.stopped()) context_.restart();
    if (context_.run_one_until(deadline) == 0 && std::chrono::steady_clock::now() >= deadline) {
      return done();
    }
  }
}

bool WsPeer::upgrade(std::chrono::milliseconds timeout) {
  if (!connected_ || !flush()) return false;
  pump([&] { return framing_.open() || framing_.failed(); },
       std::chrono::steady_clock::now() + timeout);
  return framing_.open();
}

bool WsPeer::send(const physics::wire::ClientMessage& message) {
  framing_.send_binary(message.SerializeAsString());
  return flush();
}

bool WsPeer::send_text(const std::string& text) {
  framing_.send_text(text);
  return flush();
}

bool WsPeer::ping(const std::string& payload) {
  framing_.ping(payload);
  return flush();
}

std::optional<physics::wire::ServerMessage> WsPeer::receive(std::chrono::milliseconds timeout) {
  std::optional<physics::wire::ServerMessage> result;
  bool bad = false;
  pump(
      [&] {
        WsClientFraming::Received received;
        while (!result && !bad && framing_.pop(received)) {
          if (!received.binary) {
            ++text_frames_;
            continue;
          }
          ++binary_frames_;
          physics::wire::ServerMessage message;
          if (message.ParseFromString(received.payload)) {
            result = std::move(message);
          } else {
            bad = true;
          }
        }
        return result.has_value() || bad;
      },
      std::chrono::steady_clock::now() + timeout);
  return result;
}

std::optional<physics::wire::Error> WsPeer::receive_error(std::chrono::milliseconds timeout) {
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

bool WsPeer::wait_closed(std::chrono::milliseconds timeout) {
  return pump(
      [&] {
        WsClientFraming::Received ignored;
        while (framing_.pop(ignored)) {
        }
        return closed_;
      },
      std::chrono::steady_clock::now() + timeout);
}

std::string client_frame(std::uint8_t opcode, bool fin, std::string_view payload, bool mask) {
  std::string frame;
  frame.push_back(static_cast<char>((fin ? 0x80 : 0x00) | (opcode & 0x0f)));
  const std::uint8_t mask_bit = mask ? 0x80 : 0x00;
  const std::size_t size = payload.size();
  if (size < 126) {
    frame.push_back(static_cast<char>(mask_bit | size));
  } else if (size <= 0xffff) {
    frame.push_back(static_cast<char>(mask_bit | 126));
    frame.push_back(static_cast<char>(size >> 8));
    frame.push_back(static_cast<char>(size & 0xff));
  } else {
    frame.push_back(static_cast<char>(mask_bit | 127));
    for (int shift = 56; shift >= 0; shift -= 8) {
      frame.push_back(static_cast<char>((static_cast<std::uint64_t>(size) >> shift) & 0xff));
    }
  }
  const std::array<std::uint8_t, 4> key = {0x37, 0xfa, 0x21, 0x3d};
  if (mask) frame.append(reinterpret_cast<const char*>(key.data()), key.size());
  for (std::size_t i = 0; i < size; ++i) {
    const auto byte = static_cast<std::uint8_t>(payload[i]);
    frame.push_back(static_cast<char>(mask ? byte ^ key[i % 4] : byte));
  }
  return frame;
}

}  // namespace itest
