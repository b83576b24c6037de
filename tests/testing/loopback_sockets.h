#pragma once
// Plain blocking loopback sockets with deadlines, for the link conditioner's tests:
// a sender, a receiver and a target that the tests drive byte by byte, with nothing
// of the product in between but the relay under test.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace physics_testing::test {

// A socket descriptor, closed on destruction.
class Socket {
 public:
  Socket() = default;
  explicit Socket(int fd) : fd_(fd) {}
  ~Socket();
  Socket(Socket&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  Socket& operator=(Socket&& other) noexcept;
  int fd() const { return fd_; }
  explicit operator bool() const { return fd_ >= 0; }

  // Every byte, blocking; false on an error.
  bool send_all(std::span<const std::uint8_t> bytes) const;
  // Exactly `count` bytes before `deadline`; nullopt on a timeout, error or end of stream.
  std::optional<std::vector<std::uint8_t>> receive(
      std::size_t count, std::chrono::steady_clock::time_point deadline) const;
  // True when the peer's FIN arrives (a read returns 0) before `deadline` with no
  // byte before it.
  bool receive_end(std::chrono::steady_clock::time_point deadline) const;
  // Sends from `bytes` without blocking until the path has taken nothing for `quiet`
  // (every buffer on the way is full) or all is sent; returns how much was sent.
  std::size_t send_until_full(std::span<const std::uint8_t> bytes,
                              std::chrono::milliseconds quiet) const;
  // No more sending (the peer reads the end of the stream).
  void shutdown_send() const;

 private:
  int fd_ = -1;
};

// A listening socket on 127.0.0.1 at a free port.
class Listener {
 public:
  Listener();
  std::uint16_t port() const { return port_; }
  // The next connection, or an empty Socket when none comes before `timeout`.
  Socket accept(std::chrono::milliseconds timeout) const;

 private:
  Socket socket_;
  std::uint16_t port_ = 0;
};

// A connection to 127.0.0.1:port (TCP_NODELAY), or an empty Socket.
Socket connect_loopback(std::uint16_t port);

}  // namespace physics_testing::test
