#pragma once
// The client side of RFC 6455 for the tests, by websocketpp's client role (a code
// path apart from the server's): bytes from the server in, messages and the close
// out; the upgrade request and masked frames into take_output(). No socket: WsPeer
// (ws_peer.h) does the I/O. C++17, like the server's ws_framing.cpp: websocketpp
// 0.8.2 does not build as C++20.
#include <cstdint>
#include <memory>
#include <string>

namespace itest {

class WsClientFraming {
 public:
  struct Received {
    bool binary = false;
    std::string payload;
  };

  // Writes the upgrade request for `uri` (ws://host:port/path) into take_output().
  explicit WsClientFraming(const std::string& uri);
  ~WsClientFraming();
  WsClientFraming(const WsClientFraming&) = delete;
  WsClientFraming& operator=(const WsClientFraming&) = delete;

  void feed(const char* data, std::size_t size);
  std::string take_output();
  bool open() const;
  // The upgrade failed (the server's reply was not a 101).
  bool failed() const;
  bool pop(Received& out);

  void send_binary(const std::string& payload);
  void send_text(const std::string& payload);
  void ping(const std::string& payload);
  void close(std::uint16_t code, const std::string& reason);

  // The server's close frame: its code (0: none came) and reason.
  int remote_close_code() const;
  std::string remote_close_reason() const;
  // The HTTP status of the upgrade reply (0 before it).
  int http_status() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace itest
