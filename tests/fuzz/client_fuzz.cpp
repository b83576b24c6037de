// libFuzzer harness: a hostile server. The input is the byte stream a server sends;
// a real client::Client connects to a fake server on loopback, which sends those
// bytes (whatever the Hello said) and then ends the stream. The client must never
// crash, never hang past its timeouts, and end connected or with a failure state.
//
// Covered: the whole client library's receive path as a user runs it: framing with
// its limit, ServerMessage parsing, Welcome (client/src/convert.cpp, the predictor
// and quanta it sets up), Snapshots in every encoding (wire::Reconstruction::apply,
// the view hash and the full-state request on a desync, the snapshot buffer's
// bound), Errors and Pongs with their bounds, and a few sends (input, ack, ping)
// in between, which the fake server reads and discards.
// Not covered: a server that stalls mid-stream (the client's timeouts), which the
// integration tests reach.
#include <google/protobuf/stubs/logging.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <thread>

#include "client/client.h"

namespace {

// A listening socket on 127.0.0.1, opened once for the whole run.
struct Listener {
  int fd = -1;
  std::uint16_t port = 0;
  Listener() {
    fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = 0;
    const int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) std::abort();
    if (::listen(fd, 4) != 0) std::abort();
    socklen_t length = sizeof address;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
    port = ntohs(address.sin_port);
  }
};

// Accepts one connection, writes `data`, sends FIN, and reads until the client
// closes: closing with the client's bytes unread would reset the connection, and a
// reset may destroy what the client has not read yet.
void serve_once(int listen_fd, const std::uint8_t* data, std::size_t size) {
  const int fd = ::accept(listen_fd, nullptr, nullptr);
  if (fd < 0) return;
  std::size_t sent = 0;
  while (sent < size) {
    const ssize_t n = ::send(fd, data + sent, size - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
  ::shutdown(fd, SHUT_WR);
  std::array<char, 4096> sink{};
  while (::recv(fd, sink.data(), sink.size(), 0) > 0) {
  }
  ::close(fd);
}

}  // namespace

// libprotobuf logs a line for every string field that is not UTF-8; a fuzzer makes
// millions of those.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Listener listener;
  std::thread server(serve_once, listener.fd, data, size);
  {
    client::ClientConfig config;
    config.port = listener.port;
    config.max_message_bytes = 1u << 16;
    config.max_buffered_snapshots = 8;
    config.keepalive = std::chrono::milliseconds(0);
    client::Client client(config);
    if (client.connect(std::chrono::milliseconds(2000))) {
      std::uint64_t tick = 1;
      // The fake server has sent everything and closed: each call ends at a
      // snapshot or at the end of the stream, well before the timeout.
      for (int guard = 0; guard < 100000 && client.state() == client::ConnectionState::Connected;
           ++guard) {
        const auto snapshot = client.next_snapshot(std::chrono::milliseconds(2000));
        if (!snapshot) break;
        client.send_input(tick++, 1.0, 0.0);
        client.send_ping(tick);
      }
    }
    if (client.state() == client::ConnectionState::Connected) {
      // Still connected after the server closed: only when a timeout passed.
      std::abort();
    }
  }
  server.join();
  return 0;
}
