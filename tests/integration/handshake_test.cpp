// What a stranger can hold before saying Hello: a connection gets a handshake
// deadline, a small frame limit and a pending cap of its own (in all and per
// address), so silent, dribbling or oversized handshakes never keep a player out.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "harness.h"
#include "wire/framing.h"

namespace itest {
namespace {

namespace pb = physics::wire;

// The handshake deadline of these tests, and the margin every wait for it gets: a
// loaded machine (or ThreadSanitizer) may run the housekeeping timer late.
constexpr auto kHandshake = 500ms;
constexpr auto kMargin = 5s;

server::ServerConfig handshake_config() {
  server::ServerConfig config = test_config();
  config.handshake_timeout = kHandshake;
  return config;
}

TEST(Handshake, SilentConnectionsAreClosedAtTheDeadlineAndTheSeatsStayFree) {
  server::ServerConfig config = handshake_config();
  config.max_clients = 2;
  RunningServer server(config, scene::default_scene());
  std::vector<std::unique_ptr<RawPeer>> silent;
  for (int i = 0; i < 6; ++i) silent.push_back(std::make_unique<RawPeer>(server.port()));
  // Players join while the silent ones are still open: they never count as players.
  client::Client a(server.client_config("a"));
  client::Client b(server.client_config("b"));
  ASSERT_TRUE(a.connect(3s)) << a.last_error().to_string();
  ASSERT_TRUE(b.connect(3s)) << b.last_error().to_string();
  for (auto& peer : silent) {
    auto error = peer->receive_error(kHandshake + kMargin);
    ASSERT_TRUE(error.has_value());
    EXPECT_EQ(error->code(), pb::ERROR_TOO_SLOW);
    EXPECT_TRUE(error->fatal());
    EXPECT_TRUE(peer->wait_closed(kMargin));
  }
  EXPECT_TRUE(eventually(
      [&] { return dropped(server.stats(), server::DropReason::HandshakeTimeout) == 6; }, kMargin));
  EXPECT_EQ(server.stats().connected_clients, 2u);
}

TEST(Handshake, AHelloDribbledByteByByteMissesTheDeadline) {
  RunningServer server(handshake_config(), scene::default_scene());
  RawPeer peer(server.port());
  const std::string hello = wire::encode_frame(hello_message("slow"));
  const auto started = std::chrono::steady_clock::now();
  std::size_t sent = 0;
  // One byte every 100 ms: the 20-odd bytes would take over 2 s.
  while (sent < hello.size() && !peer.closed() &&
         std::chrono::steady_clock::now() - started < kHandshake + kMargin) {
    if (!peer.send_bytes(hello.substr(sent, 1))) break;
    ++sent;
    if (auto message = peer.receive(100ms)) {
      ASSERT_TRUE(message->has_error()) << "welcomed after " << sent << " bytes";
      EXPECT_EQ(message->error().code(), pb::ERROR_TOO_SLOW);
      break;
    }
  }
  EXPECT_LT(sent, hello.size());
  EXPECT_TRUE(eventually(
      [&] { return dropped(server.stats(), server::DropReason::HandshakeTimeout) == 1; }, kMargin));
}

TEST(Handshake, ALargeFrameBeforeHelloIsRefusedAtItsPrefix) {
  RunningServer server(handshake_config(), scene::default_scene());
  RawPeer peer(server.port());
  // A prefix announcing 1 MiB - 1: fine after joining, far over the 4 KiB before.
  std::string prefix;
  wire::append_varint_prefix((1u << 20) - 1, prefix);
  ASSERT_TRUE(peer.send_bytes(prefix + std::string(1000, 'x')));
  auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MESSAGE_TOO_LARGE);
  EXPECT_NE(error->message().find("4096"), std::string::npos) << error->message();
  EXPECT_TRUE(peer.wait_closed(3s));
  // After joining the full limit applies: the client's own large frames pass.
  EXPECT_EQ(check_server_serves(server), "");
}

// Per address: a stranger on 127.0.0.2 holds at most its share of pending
// connections; a player on 127.0.0.1 joins while they are all open.
TEST(Handshake, PendingConnectionsAreCappedPerAddress) {
  server::ServerConfig config = handshake_config();
  config.handshake_timeout = 30s;  // the stranger's sockets stay open throughout
  config.max_pending_per_address = 4;
  RunningServer server(config, scene::default_scene());
  std::vector<std::unique_ptr<RawPeer>> stranger;
  for (int i = 0; i < 10; ++i) {
    stranger.push_back(std::make_unique<RawPeer>(server.port(), "127.0.0.2"));
    ASSERT_TRUE(stranger.back()->connected());
  }
  int refused = 0;
  for (auto& peer : stranger) {
    if (auto error = peer->receive_error(300ms)) {
      EXPECT_EQ(error->code(), pb::ERROR_SERVER_FULL);
      ++refused;
    }
  }
  EXPECT_EQ(refused, 6);
  client::Client player(server.client_config("player"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  EXPECT_EQ(dropped(server.stats(), server::DropReason::TooManyPending), 6u);
}

TEST(Handshake, PendingConnectionsAreCappedInAll) {
  server::ServerConfig config = handshake_config();
  config.handshake_timeout = 30s;
  config.max_pending = 3;
  config.max_pending_per_address = 100;
  RunningServer server(config, scene::default_scene());
  std::vector<std::unique_ptr<RawPeer>> pending;
  for (int i = 0; i < 5; ++i) pending.push_back(std::make_unique<RawPeer>(server.port()));
  int refused = 0;
  for (auto& peer : pending) {
    if (auto error = peer->receive_error(300ms)) {
      EXPECT_EQ(error->code(), pb::ERROR_SERVER_FULL);
      ++refused;
    }
  }
  EXPECT_EQ(refused, 2);
}

}  // namespace
}  // namespace itest
