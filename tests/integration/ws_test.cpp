// The WebSocket port: the same sessions as the TCP port behind binary frames. Real
// clients (websocketpp's client role, ws_peer.h) join, play, watch and play in
// lockstep beside TCP players; hostile ones break the transport's rules, and each is
// closed while a TCP player beside it goes on being served.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <thread>

#include "harness.h"
#include "player_beside.h"
#include "reference.h"
#include "test_scenes.h"
#include "wire/framing.h"
#include "ws_peer.h"

namespace itest {
namespace {

namespace pb = physics::wire;

// RFC 6455 close codes the server uses.
constexpr int kCloseNormal = 1000;
constexpr int kCloseProtocolError = 1002;
constexpr int kCloseUnsupportedData = 1003;
constexpr int kCloseMessageTooBig = 1009;

server::ServerConfig ws_config(bool lockstep = false) {
  server::ServerConfig config = test_config(lockstep);
  config.ws_port = 0;
  return config;
}

pb::ClientMessage ws_hello(const std::string& name, pb::Encoding encoding, bool spectate = false) {
  pb::ClientMessage message = hello_message(name);
  message.mutable_hello()->mutable_view()->set_encoding(encoding);
  message.mutable_hello()->mutable_view()->set_state_hash(true);
  message.mutable_hello()->set_spectate(spectate);
  return message;
}

pb::ClientMessage ack_message(std::uint64_t tick) {
  pb::ClientMessage message;
  message.mutable_ack()->set_tick(tick);
  return message;
}

// Upgrades and joins; the Welcome, or nullopt.
std::optional<pb::Welcome> join(WsPeer& peer, const pb::ClientMessage& hello) {
  if (!peer.upgrade() || !peer.send(hello)) return std::nullopt;
  for (int i = 0; i < 8; ++i) {
    const auto message = peer.receive(3s);
    if (!message || message->has_error()) return std::nullopt;
    if (message->has_welcome()) return message->welcome();
  }
  return std::nullopt;
}

// The next snapshot (acknowledged), skipping anything else.
std::optional<pb::Snapshot> next_snapshot(WsPeer& peer) {
  for (int i = 0; i < 16; ++i) {
    const auto message = peer.receive(5s);
    if (!message) return std::nullopt;
    if (message->has_snapshot()) {
      peer.send(ack_message(message->snapshot().tick()));
      return message->snapshot();
    }
  }
  return std::nullopt;
}

TEST(WebSocket, OffUnlessConfigured) {
  RunningServer tcp_only(test_config(), scene::default_scene());
  EXPECT_EQ(tcp_only.get().ws_port(), 0);
  RunningServer both(ws_config(), scene::default_scene());
  EXPECT_NE(both.get().ws_port(), 0);
  EXPECT_NE(both.get().ws_port(), both.port());
}

// Each message is one binary frame, both ways: the Welcome, then snapshots with
// rising ticks; inputs sent back move the player's body.
TEST(WebSocket, PlayerJoinsGetsSnapshotsAndItsBodyMovesUnderInput) {
  RunningServer server(ws_config(), free_flight_scene(false));
  WsPeer peer(server.get().ws_port());
  const auto welcome = join(peer, ws_hello("ws-player", pb::ENCODING_FULL));
  ASSERT_TRUE(welcome.has_value());
  ASSERT_NE(welcome->body_id(), 0u);
  std::uint64_t last_tick = 0;
  double first_x = 0.0;
  double last_x = 0.0;
  double last_vx = 0.0;
  for (int i = 0; i < 40; ++i) {
    const auto snapshot = next_snapshot(peer);
    ASSERT_TRUE(snapshot.has_value()) << "snapshot " << i;
    EXPECT_GT(snapshot->tick(), last_tick);
    last_tick = snapshot->tick();
    for (const pb::BodyState& body : snapshot->bodies()) {
      if (body.body_id() != welcome->body_id()) continue;
      if (i == 0) first_x = body.x();
      last_x = body.x();
      last_vx = body.vx();
    }
    ASSERT_TRUE(peer.send(input_message(snapshot->tick() + 1, 5.0, 0.0)));
  }
  EXPECT_GT(last_vx, 0.5);
  EXPECT_GT(last_x, first_x);
  EXPECT_EQ(peer.text_frames(), 0);
  EXPECT_EQ(server.stats().connected_clients, 1u);
}

// One player over TCP, one over WebSocket, in lockstep: every snapshot's state hash
// equals that of the same scene stepped in-process with the same inputs.
TEST(WebSocket, LockstepBesideATcpPlayerMatchesInProcessHashes) {
  const scene::SceneDef scene = free_flight_scene(true);
  server::ServerConfig config = ws_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;  // no tick may be stepped without both inputs
  RunningServer server(config, scene);
  client::Client tcp(server.exact_client_config("tcp-player"));
  ASSERT_TRUE(tcp.connect(3s)) << tcp.last_error().to_string();
  WsPeer ws(server.get().ws_port());
  const auto ws_welcome = join(ws, ws_hello("ws-player", pb::ENCODING_EXACT));
  ASSERT_TRUE(ws_welcome.has_value());
  ASSERT_EQ(tcp.welcome().current_tick, 0u);
  ASSERT_EQ(ws_welcome->current_tick(), 0u);

  ReferenceRun reference(scene);
  ASSERT_EQ(reference.add_player(tcp.welcome()), tcp.welcome().body_id);
  client::Welcome ws_as_client;
  ws_as_client.body_id = ws_welcome->body_id();
  for (const pb::BodyShape& shape : ws_welcome->bodies()) {
    if (shape.body_id() != ws_welcome->body_id()) continue;
    client::BodyShape body;
    body.body_id = shape.body_id();
    body.position = {shape.position().x(), shape.position().y()};
    ws_as_client.bodies.push_back(body);
  }
  ASSERT_EQ(reference.add_player(ws_as_client), ws_welcome->body_id());

  for (std::uint64_t tick = 1; tick <= 60; ++tick) {
    const double t = static_cast<double>(tick);
    const client::Vec2 a_tcp{4.0 * std::cos(0.21 * t), 4.0 * std::sin(0.21 * t) + 6.0};
    const client::Vec2 a_ws{7.0 * std::cos(0.21 * t + 1.7), 7.0 * std::sin(0.21 * t + 1.7) + 6.0};
    ASSERT_TRUE(tcp.send_input(tick, a_tcp.x, a_tcp.y));
    ASSERT_TRUE(ws.send(input_message(tick, a_ws.x, a_ws.y)));
    reference.set_input(tcp.welcome().body_id, a_tcp.x, a_tcp.y);
    reference.set_input(ws_welcome->body_id(), a_ws.x, a_ws.y);
    const std::uint64_t expected = reference.step();
    const auto tcp_snapshot = tcp.next_snapshot(5s);
    ASSERT_TRUE(tcp_snapshot.has_value()) << "tick " << tick;
    ASSERT_EQ(tcp_snapshot->tick, tick);
    ASSERT_EQ(tcp_snapshot->state_hash, expected) << "TCP, tick " << tick;
    const auto ws_snapshot = next_snapshot(ws);
    ASSERT_TRUE(ws_snapshot.has_value()) << "tick " << tick;
    ASSERT_EQ(ws_snapshot->tick(), tick);
    ASSERT_EQ(ws_snapshot->state_hash(), expected) << "WebSocket, tick " << tick;
    EXPECT_EQ(ws_snapshot->last_applied_input_tick(), tick);
  }
  EXPECT_EQ(server.stats().lockstep_timeouts, 0u);
}

TEST(WebSocket, SpectatorWatchesATcpPlayer) {
  RunningServer server(ws_config(), free_flight_scene(false));
  PlayerBeside player(server);
  ASSERT_TRUE(player.joined()) << player.last_error();
  WsPeer spectator(server.get().ws_port());
  const auto welcome = join(spectator, ws_hello("ws-spectator", pb::ENCODING_FULL, true));
  ASSERT_TRUE(welcome.has_value());
  EXPECT_TRUE(welcome->spectator());
  EXPECT_EQ(welcome->body_id(), 0u);
  std::uint64_t last_tick = 0;
  for (int i = 0; i < 10; ++i) {
    const auto snapshot = next_snapshot(spectator);
    ASSERT_TRUE(snapshot.has_value());
    EXPECT_GT(snapshot->tick(), last_tick);
    last_tick = snapshot->tick();
    EXPECT_EQ(snapshot->bodies_size(), 1);  // the player's body, watched
  }
  EXPECT_TRUE(eventually([&] { return server.stats().spectators == 1; }));
}

TEST(WebSocket, BadHelloIsAnsweredWithAnErrorFrameThenAClose) {
  RunningServer server(ws_config(), scene::default_scene());
  WsPeer peer(server.get().ws_port());
  ASSERT_TRUE(peer.upgrade());
  pb::ClientMessage hello = hello_message("old");
  hello.mutable_hello()->set_protocol_version(999);
  ASSERT_TRUE(peer.send(hello));
  const auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_PROTOCOL_VERSION);
  EXPECT_TRUE(error->fatal());
  EXPECT_TRUE(peer.wait_closed(3s));
  EXPECT_EQ(peer.close_code(), kCloseNormal);
  EXPECT_EQ(peer.binary_frames(), 1);
  EXPECT_TRUE(eventually(
      [&] { return dropped(server.stats(), server::DropReason::ProtocolVersion) == 1; }));
}

// ---- hostile clients: each is closed, and a TCP player beside it is served ----

class WebSocketHostile : public ::testing::Test {
 protected:
  void start(server::ServerConfig config) {
    server_ = std::make_unique<RunningServer>(config, scene::default_scene());
    player_ = std::make_unique<PlayerBeside>(*server_);
    ASSERT_TRUE(player_->joined()) << player_->last_error();
  }
  void start() { start(ws_config()); }
  void expect_player_served() {
    EXPECT_TRUE(player_->gets_snapshots(5)) << "the TCP player beside";
    EXPECT_TRUE(player_->connected());
  }
  std::uint64_t drops(server::DropReason reason) { return dropped(server_->stats(), reason); }
  std::uint16_t ws_port() { return server_->get().ws_port(); }

  std::unique_ptr<RunningServer> server_;
  std::unique_ptr<PlayerBeside> player_;
};

// Over the limit (the Hello's before joining, max_message_bytes after): an Error,
// then close code 1009, as soon as the frame header that announces it is read.
TEST_F(WebSocketHostile, OversizedMessagesAreRefusedBeforeAndAfterJoining) {
  server::ServerConfig config = ws_config();
  config.max_hello_bytes = 256;
  config.max_message_bytes = 1024;
  start(config);
  WsPeer stranger(ws_port());
  ASSERT_TRUE(stranger.upgrade());
  ASSERT_TRUE(stranger.send_raw(client_frame(0x2, true, std::string(257, 'x'))));
  auto error = stranger.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MESSAGE_TOO_LARGE);
  EXPECT_TRUE(stranger.wait_closed(3s));
  EXPECT_EQ(stranger.close_code(), kCloseMessageTooBig);

  WsPeer player(ws_port());
  ASSERT_TRUE(join(player, ws_hello("big", pb::ENCODING_PREDICTED)).has_value());
  ASSERT_TRUE(player.send_raw(client_frame(0x2, true, std::string(1025, 'x'))));
  error = player.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MESSAGE_TOO_LARGE);
  EXPECT_TRUE(player.wait_closed(3s));
  EXPECT_EQ(player.close_code(), kCloseMessageTooBig);
  EXPECT_TRUE(eventually([&] { return drops(server::DropReason::MessageTooLarge) == 2; }));
  expect_player_served();
}

// A message in continuation frames is reassembled, and the limit is on the whole
// message: fragments each under it, adding up to more, are refused.
TEST_F(WebSocketHostile, FragmentedMessagesAreReassembledWithinTheLimit) {
  server::ServerConfig config = ws_config();
  config.max_hello_bytes = 256;
  start(config);
  WsPeer fragmented(ws_port());
  ASSERT_TRUE(fragmented.upgrade());
  const std::string hello = ws_hello("in-pieces", pb::ENCODING_PREDICTED).SerializeAsString();
  ASSERT_TRUE(fragmented.send_raw(client_frame(0x2, false, hello.substr(0, 3)) +
                                  client_frame(0x0, false, hello.substr(3, 5)) +
                                  client_frame(0x0, true, hello.substr(8))));
  const auto welcome = fragmented.receive(3s);
  ASSERT_TRUE(welcome.has_value());
  EXPECT_TRUE(welcome->has_welcome());

  WsPeer too_many(ws_port());
  ASSERT_TRUE(too_many.upgrade());
  std::string frames = client_frame(0x2, false, std::string(200, 'x'));
  for (int i = 0; i < 4; ++i) frames += client_frame(0x0, false, std::string(200, 'x'));
  frames += client_frame(0x0, true, "x");
  ASSERT_TRUE(too_many.send_raw(frames));
  const auto error = too_many.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MESSAGE_TOO_LARGE);
  EXPECT_TRUE(too_many.wait_closed(3s));
  EXPECT_EQ(too_many.close_code(), kCloseMessageTooBig);
  expect_player_served();
}

// The upgrade request a byte at a time, slower than the handshake deadline: the
// deadline counts from the connection, upgrade included, as on the TCP port.
TEST_F(WebSocketHostile, UpgradeDribbledPastTheHandshakeDeadlineIsClosed) {
  server::ServerConfig config = ws_config();
  config.handshake_timeout = 300ms;
  start(config);
  WsPeer dribbler(ws_port());
  const std::string request = dribbler.take_upgrade_request();
  ASSERT_GT(request.size(), 100u);
  // 20 ms a byte: the whole request would take over 2 s. The dribble is the attack.
  for (std::size_t i = 0; i < request.size() && !dribbler.closed(); ++i) {
    if (!dribbler.send_raw(request.substr(i, 1))) break;
    std::this_thread::sleep_for(20ms);
    if (i % 10 == 0 && drops(server::DropReason::HandshakeTimeout) > 0) break;
  }
  EXPECT_TRUE(dribbler.wait_closed(3s));
  EXPECT_EQ(dribbler.raw_received(), "");  // never upgraded, nothing said
  EXPECT_TRUE(eventually([&] { return drops(server::DropReason::HandshakeTimeout) == 1; }));
  expect_player_served();
}

TEST_F(WebSocketHostile, UnmaskedFramesAreAProtocolError) {
  start();
  WsPeer peer(ws_port());
  ASSERT_TRUE(peer.upgrade());
  ASSERT_TRUE(peer.send_raw(
      client_frame(0x2, true, ws_hello("bare", pb::ENCODING_PREDICTED).SerializeAsString(),
                   /*mask=*/false)));
  const auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MALFORMED);
  EXPECT_TRUE(peer.wait_closed(3s));
  EXPECT_EQ(peer.close_code(), kCloseProtocolError);
  EXPECT_TRUE(eventually([&] { return drops(server::DropReason::Malformed) == 1; }));
  expect_player_served();
}

TEST_F(WebSocketHostile, TextFramesAreRefused) {
  start();
  WsPeer peer(ws_port());
  ASSERT_TRUE(peer.upgrade());
  ASSERT_TRUE(peer.send_text(ws_hello("texter", pb::ENCODING_PREDICTED).DebugString()));
  const auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MALFORMED);
  EXPECT_TRUE(peer.wait_closed(3s));
  EXPECT_EQ(peer.close_code(), kCloseUnsupportedData);
  EXPECT_TRUE(eventually([&] { return drops(server::DropReason::Malformed) == 1; }));
  expect_player_served();
}

// Pings count against the message rate like messages: a flood pauses the
// connection's reading (throttled), each ping still gets its pong in turn, and the
// session is served again once the flood is paid for.
TEST_F(WebSocketHostile, PingFloodIsThrottledByTheMessageRate) {
  server::ServerConfig config = ws_config();
  config.peer_messages_per_second = 400;
  config.peer_message_burst = 100;
  start(config);
  WsPeer flooder(ws_port());
  ASSERT_TRUE(join(flooder, ws_hello("flooder", pb::ENCODING_PREDICTED)).has_value());
  std::string flood;
  for (int i = 0; i < 600; ++i) flood += client_frame(0x9, true, "");
  ASSERT_TRUE(flooder.send_raw(flood));
  pb::ClientMessage ping;
  ping.mutable_ping()->set_nonce(42);
  ASSERT_TRUE(flooder.send(ping));
  EXPECT_TRUE(eventually([&] { return server_->stats().throttled_reads > 0; }));
  bool ponged = false;
  for (int i = 0; i < 400 && !ponged; ++i) {
    const auto message = flooder.receive(5s);
    if (!message) break;
    ponged = message->has_pong() && message->pong().nonce() == 42;
    if (message->has_snapshot()) flooder.send(ack_message(message->snapshot().tick()));
  }
  EXPECT_TRUE(ponged) << "served again after the flood";
  expect_player_served();
}

TEST_F(WebSocketHostile, PlainHttpRequestIsRefused) {
  start();
  WsPeer peer(ws_port());
  ASSERT_TRUE(peer.send_raw("GET /index.html HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"));
  EXPECT_TRUE(peer.wait_closed(3s));
  EXPECT_EQ(peer.raw_received().rfind("HTTP/1.1 4", 0), 0u) << peer.raw_received();
  EXPECT_TRUE(eventually([&] { return drops(server::DropReason::Malformed) == 1; }));
  expect_player_served();
}

// Bytes that are not HTTP, with a line's end or without (a TCP client's Hello, sent
// to the wrong port): answered 400 at once, and closed.
TEST_F(WebSocketHostile, GarbageBytesAreRefused) {
  start();
  std::string garbage;
  for (int i = 0; i < 2000; ++i) garbage.push_back(static_cast<char>((i * 131 + 7) % 256));
  WsPeer line(ws_port());
  line.send_raw(garbage + "\r\n\r\n");  // the server may close before it has all
  EXPECT_TRUE(line.wait_closed(3s));
  EXPECT_EQ(line.raw_received().rfind("HTTP/1.1 400", 0), 0u) << line.raw_received();

  WsPeer tcp_client(ws_port());
  ASSERT_TRUE(tcp_client.send_raw(wire::encode_frame(hello_message("wrong-port"))));
  EXPECT_TRUE(tcp_client.wait_closed(3s));
  EXPECT_EQ(tcp_client.raw_received().rfind("HTTP/1.1 400", 0), 0u) << tcp_client.raw_received();
  EXPECT_TRUE(eventually([&] { return drops(server::DropReason::Malformed) == 2; }));
  expect_player_served();
}

}  // namespace
}  // namespace itest
