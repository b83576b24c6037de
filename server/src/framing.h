#pragma once
// What a Session needs from the bytes of its transport, whatever they carry: incoming
// bytes in, whole ClientMessage encodings (and the transport's own control events)
// out; the bytes that go before each outgoing message; and the bytes the transport
// writes on its own (a WebSocket's upgrade reply, pongs, close frames). Two kinds:
// the TCP port's varint length prefix (tcp_framing.h) and the WebSocket port's
// binary frames (ws_framing.h). The Session keeps everything else (the socket, the
// limits, the write queue, the close), so both ports obey the same rules.
//
// This header is C++17: ws_framing.cpp includes it, and is compiled as C++17 (see
// server/CMakeLists.txt).
#include <cstddef>
#include <cstdint>
#include <string>

namespace server {

class Framing {
 public:
  enum class Status {
    NeedMore,    // nothing more until more bytes are fed
    Message,     // `out` holds one message's bytes
    Control,     // a control frame (WebSocket ping or pong) the transport handled
    TooLarge,    // a message over the limit; `out` says which; the stream is unusable
    Malformed,   // bytes that break the transport's rules; `out` says how
    PeerClosed,  // the peer closed the stream cleanly (WebSocket close frame)
  };

  virtual ~Framing() = default;
  // Appends received bytes; call next() until it returns NeedMore.
  virtual void feed(const std::uint8_t* data, std::size_t size) = 0;
  virtual Status next(std::string& out) = 0;
  virtual void set_max_message_bytes(std::size_t max) = 0;
  // True once messages can be sent (a WebSocket, once upgraded).
  virtual bool open() const = 0;
  // The bytes before a message of `payload_bytes` bytes.
  virtual std::string header(std::size_t payload_bytes) const = 0;
  // Bytes the transport wrote on its own since the last call, to go out next.
  virtual std::string take_output() = 0;
  // Begins the transport's own close (a WebSocket close frame, into take_output()).
  virtual void close() = 0;
};

}  // namespace server
