// The server's own socket layer on a loopback port, driven by raw sockets: the port
// it binds, frames larger than one write, and the idle timer of a client that sends
// nothing. What clients see of the server (the handshake, refusals, bad input, slow
// readers, lockstep, shutdown) is tested through the client library and raw peers
// in tests/integration/. Waits are bounded polls on what the server reports, never
// fixed sleeps.
#include <gtest/gtest.h>

#include <thread>

#include "server/server.h"
#include "socket_client.h"
#include "test_scene.h"

namespace {

using namespace std::chrono_literals;
using server_test::SocketClient;

struct RunningServer {
  explicit RunningServer(server::ServerConfig config,
                         scene::SceneDef scene = server_test::free_space_scene())
      : server((config.port = 0, config), std::move(scene)), thread([this] { server.run(); }) {}
  ~RunningServer() {
    server.stop();
    thread.join();
  }
  std::uint16_t port() const { return server.port(); }
  server::Server server;
  std::thread thread;
};

template <typename Condition>
bool eventually(Condition condition, std::chrono::milliseconds timeout = 5000ms) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return condition();
}

// The next snapshot, acknowledged (the server sends no more than a window of
// snapshots that were not).
std::optional<physics::wire::Snapshot> next_snapshot(SocketClient& client) {
  for (int i = 0; i < 1000; ++i) {
    const auto message = client.receive();
    if (!message) return std::nullopt;
    if (message->has_snapshot()) {
      physics::wire::ClientMessage ack;
      ack.mutable_ack()->set_tick(message->snapshot().tick());
      client.send(ack);
      return message->snapshot();
    }
  }
  return std::nullopt;
}

std::uint64_t drops(const server::Server& s, server::DropReason reason) {
  const auto stats = s.stats();
  const auto it = stats.dropped.find(reason);
  return it == stats.dropped.end() ? 0 : it->second;
}

TEST(ServerSocket, PortZeroPicksAFreePortAndABusyPortIsAClearError) {
  RunningServer running({});
  EXPECT_NE(running.port(), 0);
  server::ServerConfig same;
  same.port = running.port();
  try {
    server::Server second(same, server_test::free_space_scene());
    FAIL() << "a second server bound the same port";
  } catch (const std::system_error& error) {
    EXPECT_NE(std::string(error.what()).find(std::to_string(running.port())), std::string::npos)
        << error.what();
  }
}

TEST(ServerSocket, ClientThatSendsNothingIsDroppedAsIdle) {
  server::ServerConfig config;
  config.idle_timeout = 300ms;
  RunningServer running(config);
  // The server's idle clock starts no earlier than the connect, so the Error cannot
  // come sooner than one timeout after this; every wait for it or for the drop is
  // bounded by 20 timeouts (6 s), a margin for a slow machine or ThreadSanitizer.
  const auto connected = std::chrono::steady_clock::now();
  const auto margin = 20 * config.idle_timeout;
  SocketClient quiet(running.port());
  ASSERT_TRUE(quiet.join("quiet"));
  std::optional<physics::wire::Error> error;
  for (auto left = margin; !error && left > 0ms;
       left = std::chrono::duration_cast<std::chrono::milliseconds>(
           connected + margin - std::chrono::steady_clock::now())) {
    const auto message = quiet.receive(left);  // snapshots (not acknowledged), the Error
    if (!message) break;
    if (message->has_error()) error = message->error();
  }
  const auto waited = std::chrono::steady_clock::now() - connected;
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_TOO_SLOW);
  EXPECT_GE(waited, config.idle_timeout) << "dropped before the idle timeout";
  EXPECT_TRUE(quiet.wait_closed(margin));
  EXPECT_TRUE(
      eventually([&] { return drops(running.server, server::DropReason::Idle) == 1; }, margin));
  EXPECT_TRUE(eventually([&] { return running.server.stats().connected_clients == 0; }, margin));
}

TEST(ServerSocket, FramesLargerThanOneWriteArriveWhole) {
  // 3000 balls: a Welcome of ~150 kB and snapshots of ~130 kB, far more than one
  // write_some moves, so every frame is written in several pieces.
  scene::SceneDef scene = server_test::free_space_scene();
  for (int i = 0; i < 3000; ++i) {
    phys::BodyDef ball = scene.player;
    ball.position = {static_cast<double>(i % 60) * 3.0, 100.0 + static_cast<double>(i / 60) * 3.0};
    scene.bodies.push_back(ball);
  }
  server::ServerConfig config;
  config.socket_send_buffer_bytes = 16384;  // no frame fits in the kernel at once
  RunningServer running(config, scene);
  SocketClient first(running.port());
  SocketClient second(running.port());
  const auto w1 = first.join("first");
  const auto w2 = second.join("second");
  ASSERT_TRUE(w1 && w2);
  EXPECT_EQ(w1->bodies_size(), 3001);
  for (int i = 0; i < 10; ++i) {
    for (SocketClient* client : {&first, &second}) {
      const auto snapshot = next_snapshot(*client);
      ASSERT_TRUE(snapshot) << "snapshot " << i;
      // 3000 balls and one or two players (the first may see ticks before the second).
      EXPECT_GE(snapshot->bodies_size(), 3001);
      EXPECT_LE(snapshot->bodies_size(), 3002);
    }
  }
}

}  // namespace
