#pragma once
// A minimal blocking client for the server's own socket tests: raw bytes out,
// framed ServerMessages in, every wait bounded by a timeout.
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "wire.pb.h"
#include "wire/framing.h"

namespace server_test {

class SocketClient {
 public:
  explicit SocketClient(std::uint16_t port);

  void send_raw(const std::string& bytes);
  void send(const physics::wire::ClientMessage& message);
  // The next message, or nullopt on end of stream, error or timeout.
  std::optional<physics::wire::ServerMessage> receive(
      std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
  // Reads (and discards) until the server closes; false on timeout.
  bool wait_closed(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
  // Hello (asking for ENCODING_FULL, so that every snapshot lists every dynamic
  // body), then the Welcome (nullopt if something else came).
  std::optional<physics::wire::Welcome> join(const std::string& name);

 private:
  // One read of whatever is there; false on end of stream, error or timeout.
  bool read_some(std::chrono::steady_clock::time_point deadline);

  asio::io_context io_;
  asio::ip::tcp::socket socket_;
  wire::FrameReader reader_{std::size_t{64} << 20};
  std::array<std::uint8_t, 65536> buffer_{};
  bool closed_ = false;
};

// A Hello asking for ENCODING_FULL, the world's state hash in every snapshot, and
// the largest window the server allows by default (64 snapshots).
physics::wire::ClientMessage full_view_hello(const std::string& name);

}  // namespace server_test
