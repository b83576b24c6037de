// How a WebSocket session ends when the client is done (RFC 6455 7.1): a Bye is
// answered with a close frame (1000) and the server closes the TCP connection; a
// client's close frame is answered with one, and its body leaves the world as soon as
// that is written, not when the client's TCP side closes or close_linger runs out.
// And unsolicited pongs count against the message rate like any message.
#include <gtest/gtest.h>

#include <string>

#include "harness.h"
#include "player_beside.h"
#include "ws_peer.h"

namespace itest {
namespace {

namespace pb = physics::wire;

constexpr int kCloseNormal = 1000;

// A linger far longer than any wait below: a session left to it would fail them.
server::ServerConfig ws_config_long_linger() {
  server::ServerConfig config = test_config();
  config.ws_port = 0;
  config.close_linger = std::chrono::milliseconds(60000);
  return config;
}

bool join(WsPeer& peer, const std::string& name) {
  if (!peer.upgrade() || !peer.send(hello_message(name))) return false;
  for (int i = 0; i < 8; ++i) {
    const auto message = peer.receive(3s);
    if (!message || message->has_error()) return false;
    if (message->has_welcome()) return true;
  }
  return false;
}

TEST(WebSocketClose, AByeIsAnsweredWithACloseFrameAndTheBodyLeaves) {
  RunningServer server(ws_config_long_linger(), scene::default_scene());
  WsPeer peer(server.get().ws_port());
  ASSERT_TRUE(join(peer, "leaving"));
  ASSERT_TRUE(eventually([&] { return server.stats().connected_clients == 1; }));
  pb::ClientMessage bye;
  bye.mutable_bye()->set_reason("done");
  ASSERT_TRUE(peer.send(bye));
  EXPECT_TRUE(peer.wait_closed(5s));
  EXPECT_EQ(peer.close_code(), kCloseNormal) << "no close frame after the Bye";
  EXPECT_TRUE(eventually([&] { return server.stats().connected_clients == 0; }));
  EXPECT_TRUE(
      eventually([&] { return dropped(server.stats(), server::DropReason::ClientBye) == 1; }));
}

TEST(WebSocketClose, AClientsCloseFrameIsAnsweredAndItsBodyLeavesAtOnce) {
  RunningServer server(ws_config_long_linger(), scene::default_scene());
  WsPeer peer(server.get().ws_port());
  ASSERT_TRUE(join(peer, "closing"));
  ASSERT_TRUE(eventually([&] { return server.stats().connected_clients == 1; }));
  // Close code 1000, big-endian; the client keeps its TCP side open.
  ASSERT_TRUE(peer.send_raw(client_frame(0x8, true, std::string("\x03\xE8", 2))));
  EXPECT_TRUE(eventually([&] { return server.stats().connected_clients == 0; }))
      << "the body waits for the client's TCP close or close_linger";
  EXPECT_TRUE(peer.wait_closed(5s)) << "the server closes the TCP connection first";
  EXPECT_EQ(peer.close_code(), kCloseNormal);
}

// As a ping flood (ws_test.cpp): pongs nobody asked for pause the connection's
// reading once over the rate, and the player beside is served throughout.
TEST(WebSocketClose, UnsolicitedPongsCountAgainstTheMessageRate) {
  server::ServerConfig config = test_config();
  config.ws_port = 0;
  config.peer_messages_per_second = 400;
  config.peer_message_burst = 100;
  RunningServer server(config, scene::default_scene());
  PlayerBeside player(server);
  ASSERT_TRUE(player.joined()) << player.last_error();
  WsPeer flooder(server.get().ws_port());
  ASSERT_TRUE(join(flooder, "flooder"));
  std::string flood;
  for (int i = 0; i < 600; ++i) flood += client_frame(0xA, true, "");
  ASSERT_TRUE(flooder.send_raw(flood));
  EXPECT_TRUE(eventually([&] { return server.stats().throttled_reads > 0; }));
  EXPECT_TRUE(player.gets_snapshots(5));
}

}  // namespace
}  // namespace itest
