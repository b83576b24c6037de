#pragma once
// The WebSocket port's framing (RFC 6455, by websocketpp): the HTTP upgrade, then one
// ClientMessage per binary message from the client and one ServerMessage per binary
// frame to it, with no length prefix. websocketpp runs here without a socket of its
// own (its iostream transport): the Session reads and writes the TCP socket as on
// the TCP port, and this class turns the bytes read into messages, and writes the
// upgrade reply, pongs and close frames into take_output(). Pings and pongs come out
// of next() as Control, so that they count against the message rate like messages;
// text frames are Malformed (binary only). Messages over the limit (fragmented or
// not: the library reassembles them) are TooLarge as soon as the frame header that
// crosses it is read.
//
// C++17, like framing.h: websocketpp 0.8.2 does not build as C++20.
#include <memory>

#include "framing.h"

namespace server {

class WsFraming final : public Framing {
 public:
  explicit WsFraming(std::size_t max_message_bytes);
  ~WsFraming() override;
  WsFraming(const WsFraming&) = delete;
  WsFraming& operator=(const WsFraming&) = delete;

  void feed(const std::uint8_t* data, std::size_t size) override;
  Status next(std::string& out) override;
  void set_max_message_bytes(std::size_t max) override;
  bool open() const override;
  std::string header(std::size_t payload_bytes) const override;
  std::string take_output() override;
  void close() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace server
