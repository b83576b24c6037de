#pragma once
// What every integration test needs: a real server::Server on port 0 on its own
// thread (stopped and joined at the end), a raw socket for sending bytes the
// client library would never send, and waits with deadlines instead of sleeps.
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

#include "client/client.h"
#include "physics_testing/in_process_server.h"
#include "scene/scene.h"
#include "server/server.h"
#include "wire.pb.h"
#include "wire/framing.h"

namespace itest {

using namespace std::chrono_literals;

// A server running on its own thread for the lifetime of this object: physics::
// testing's InProcessServer, the one users' own tests use, with this suite's
// argument order.
class RunningServer {
 public:
  RunningServer(server::ServerConfig config, scene::SceneDef scene)
      : server_(std::move(scene), std::move(config)) {}

  std::uint16_t port() const { return server_.port(); }
  server::ServerStats stats() const { return server_.stats(); }
  server::Server& get() { return server_.server(); }
  // Stops the server and joins its thread: returns once run() has returned.
  void stop() { server_.stop(); }
  // A client config pointing at this server.
  client::ClientConfig client_config(const std::string& name = "test-client") const {
    return server_.client_config(name);
  }
  // The same, asking for exact state and the world's state hash in every snapshot:
  // for tests that compare a networked run with an in-process one bit for bit.
  client::ClientConfig exact_client_config(const std::string& name = "test-client") const {
    return server_.exact_client_config(name);
  }

 private:
  physics_testing::InProcessServer server_;
};

// A config for tests: port 0 and the given mode; everything else default.
server::ServerConfig test_config(bool lockstep = false);

// Polls `done` (a cheap check such as a stats() read) until true or the deadline.
// For conditions that have no event to wait on; never a fixed sleep.
bool eventually(const std::function<bool()>& done, std::chrono::milliseconds timeout = 3s);

// How many sessions ended for `reason` (0 when none did).
std::uint64_t dropped(const server::ServerStats& stats, server::DropReason reason);

// A TCP connection that speaks raw bytes: for the bad-input tests.
class RawPeer {
 public:
  explicit RawPeer(std::uint16_t port);
  // Connects from `local_address` (another loopback address, such as 127.0.0.2, to
  // test the per-address limits).
  RawPeer(std::uint16_t port, const std::string& local_address);
  ~RawPeer();
  bool connected() const { return connected_; }
  // True when every byte was written (false once the server has closed).
  bool send_bytes(std::string_view bytes);
  bool send(const physics::wire::ClientMessage& message);
  // The next whole message from the server; nullopt on timeout or close.
  std::optional<physics::wire::ServerMessage> receive(std::chrono::milliseconds timeout);
  // The next Error, skipping snapshots and other messages; nullopt if none came.
  std::optional<physics::wire::Error> receive_error(std::chrono::milliseconds timeout);
  // Reads (and discards) until the server closes the connection. False on timeout.
  bool wait_closed(std::chrono::milliseconds timeout);
  bool closed() const { return closed_; }
  // Shrinks the receive buffer (set before much arrives): used by "never reads".
  void set_receive_buffer(int bytes);
  // Sends FIN: the server sees the end of the stream after what was sent.
  void shutdown_send();
  void close();

 private:
  void start_read();
  asio::io_context context_;
  asio::ip::tcp::socket socket_{context_};
  wire::FrameReader reader_{64u << 20};
  std::array<std::uint8_t, 64 * 1024> buffer_{};
  bool connected_ = false;
  bool closed_ = false;
  bool reading_ = false;
};

physics::wire::ClientMessage hello_message(const std::string& name = "raw",
                                           const std::string& token = {});
physics::wire::ClientMessage input_message(std::uint64_t tick, double ax, double ay);

// Connects a fresh client and checks that the server serves it: Welcome, then
// snapshots with rising ticks that hold its own body. Returns "" or what failed.
std::string check_server_serves(const RunningServer& server, const std::string& name = "probe");

}  // namespace itest
