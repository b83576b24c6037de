#pragma once
// A WebSocket client for the tests of the server's WebSocket port: websocketpp's
// client role (ws_client_framing.h) over a plain Asio socket, with the deadlines of
// RawPeer. Besides the well-behaved calls, it can write raw bytes to the socket (for
// frames no library would send) and shows every byte the server wrote.
#include <array>
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "wire.pb.h"
#include "ws_client_framing.h"

namespace itest {

using namespace std::chrono_literals;

class WsPeer {
 public:
  explicit WsPeer(std::uint16_t port, const std::string& path = "/");
  ~WsPeer();
  bool connected() const { return connected_; }
  // Sends the upgrade request and waits for the reply: true once open.
  bool upgrade(std::chrono::milliseconds timeout = 3s);
  // The upgrade request, for sending by other means (send_raw); then upgrade() waits.
  std::string take_upgrade_request() { return framing_.take_output(); }
  // One binary frame holding the message.
  bool send(const physics::wire::ClientMessage& message);
  bool send_text(const std::string& text);
  bool ping(const std::string& payload = {});
  // Straight to the socket, around the library.
  bool send_raw(std::string_view bytes);
  // The next binary message, parsed; nullopt on timeout, close or a bad message.
  std::optional<physics::wire::ServerMessage> receive(std::chrono::milliseconds timeout);
  std::optional<physics::wire::Error> receive_error(std::chrono::milliseconds timeout);
  // Reads until the server closes the TCP connection. False on timeout.
  bool wait_closed(std::chrono::milliseconds timeout);
  bool closed() const { return closed_; }
  // The server's close frame (0: none) and the HTTP status of its reply (0: none).
  int close_code() const { return framing_.remote_close_code(); }
  std::string close_reason() const { return framing_.remote_close_reason(); }
  int http_status() const { return framing_.http_status(); }
  // Every byte the server wrote, in order.
  const std::string& raw_received() const { return raw_; }
  // Text frames received (the server sends none).
  int text_frames() const { return text_frames_; }
  // Messages the server sent that were binary frames.
  int binary_frames() const { return binary_frames_; }

 private:
  bool flush();
  // Runs the socket until `done` or the deadline.
  template <class Done>
  bool pump(Done&& done, std::chrono::steady_clock::time_point deadline);
  void start_read();

  asio::io_context context_;
  asio::ip::tcp::socket socket_{context_};
  WsClientFraming framing_;
  std::array<char, 64 * 1024> buffer_{};
  std::string raw_;
  bool connected_ = false;
  bool closed_ = false;
  bool reading_ = false;
  int text_frames_ = 0;
  int binary_frames_ = 0;
};

// A masked client frame built by hand: for the frames websocketpp's client never
// sends (unfragmented or not, any opcode). `mask` false leaves it unmasked.
std::string client_frame(std::uint8_t opcode, bool fin, std::string_view payload, bool mask = true);

}  // namespace itest
