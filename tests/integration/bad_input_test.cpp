// Bad input, each its own test. Every test runs a real server with a well-behaved
// bystander client connected; after the attack the bystander is still served, a
// fresh client is served, and the server holds no more connections than it should.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <set>

#include "harness.h"
#include "test_scenes.h"
#include "wire/messages.h"

namespace itest {
namespace {

namespace pb = physics::wire;

std::string varint(std::uint64_t value) {
  std::string out;
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7F) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
  return out;
}

class BadInput : public ::testing::Test {
 protected:
  void start(server::ServerConfig config = test_config(),
             scene::SceneDef scene = scene::default_scene()) {
    max_queued_snapshots_ = 12;  // the default window: no client holds more
    server_ = std::make_unique<RunningServer>(config, std::move(scene));
    bystander_ = std::make_unique<client::Client>(server_->client_config("bystander"));
    ASSERT_TRUE(bystander_->connect(3s)) << bystander_->last_error().to_string();
    auto first = bystander_->next_snapshot(3s);
    ASSERT_TRUE(first.has_value());
    bystander_tick_ = first->tick;
  }

  // The checks every bad-input test ends with.
  void TearDown() override {
    if (!server_ || HasFatalFailure()) return;
    // The bystander is still in its session and still gets new ticks.
    auto snapshot = bystander_->newest_snapshot(3s);
    ASSERT_TRUE(snapshot.has_value()) << bystander_->last_error().to_string();
    EXPECT_EQ(bystander_->state(), client::ConnectionState::Connected);
    EXPECT_GT(snapshot->tick, bystander_tick_);
    EXPECT_NE(snapshot->find(bystander_->welcome().body_id), nullptr);
    // A fresh client is served correctly.
    EXPECT_EQ(check_server_serves(*server_), "");
    // Queues stayed bounded, and nothing is left behind: only the bystander's
    // connection stays open.
    EXPECT_LE(server_->stats().peak_queued_snapshots, max_queued_snapshots_ + 1);
    EXPECT_TRUE(eventually([&] {
      const auto stats = server_->stats();
      return stats.open_connections == 1 && stats.connected_clients == 1;
    })) << "open "
        << server_->stats().open_connections << ", joined " << server_->stats().connected_clients;
  }

  // Waits until the bystander's snapshots no longer hold `body` (it was removed).
  bool body_removed(std::uint64_t body) {
    return bystander_
        ->wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.find(body) == nullptr; })
        .has_value();
  }

  std::unique_ptr<RunningServer> server_;
  std::unique_ptr<client::Client> bystander_;
  std::uint64_t bystander_tick_ = 0;
  std::size_t max_queued_snapshots_ = 0;
};

// What PROTOCOL.md (1.1, 3.1, 3.6) says the server answers a stream of bytes sent
// before Hello and then ended: an Error code, or none when the stream ends inside
// a frame (a connection that breaks mid-frame is closed without a message).
std::optional<pb::ErrorCode> documented_reply(const std::string& bytes) {
  std::uint64_t length = 0;
  std::size_t at = 0;
  for (int shift = 0;; shift += 7, ++at) {
    if (at == bytes.size()) return std::nullopt;  // cut off inside the prefix
    if (at == 10) return pb::ERROR_MALFORMED;     // longer than 10 bytes
    const auto byte = static_cast<std::uint8_t>(bytes[at]);
    if (shift == 63 && (byte & 0x7E) != 0) return pb::ERROR_MALFORMED;  // over 64 bits
    length |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
    if ((byte & 0x80) == 0) break;
  }
  ++at;
  // Before Hello the frame limit is max_hello_bytes (4 KiB), not max_message_bytes.
  if (length > server::ServerConfig{}.max_hello_bytes) return pb::ERROR_MESSAGE_TOO_LARGE;
  if (bytes.size() - at < length) return std::nullopt;  // cut off inside the frame
  pb::ClientMessage message;
  if (!wire::parse_client_message(bytes.substr(at, length), message)) return pb::ERROR_MALFORMED;
  if (message.kind_case() == pb::ClientMessage::KIND_NOT_SET) return pb::ERROR_MALFORMED;
  if (message.kind_case() != pb::ClientMessage::kHello) return pb::ERROR_UNEXPECTED_MESSAGE;
  return pb::ERROR_PROTOCOL_VERSION;  // random bytes never spell a valid Hello
}

TEST_F(BadInput, RandomBytesBeforeHelloGetTheErrorTheProtocolNamesAndAClose) {
  start();
  int errors = 0;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    std::mt19937 random(seed);
    // 16 streams of random bytes, and 4 whose prefix promises 100 bytes of which
    // only 50 come before the end of the stream.
    std::string garbage = seed <= 16 ? std::string(2048, '\0') : "\x64" + std::string(50, '\0');
    for (std::size_t i = seed <= 16 ? 0 : 1; i < garbage.size(); ++i) {
      garbage[i] = static_cast<char>(random() & 0xFF);
    }
    const std::optional<pb::ErrorCode> expected = documented_reply(garbage);
    RawPeer peer(server_->port());
    ASSERT_TRUE(peer.connected());
    peer.send_bytes(garbage);
    // Then the end of the stream: garbage whose length prefix promises more than was
    // sent (up to 1 MiB) is cut off, and the server must see that too.
    peer.shutdown_send();
    const auto error = peer.receive_error(3s);
    if (expected) {
      ASSERT_TRUE(error.has_value()) << "seed " << seed << ": expected " << *expected;
      EXPECT_EQ(error->code(), *expected) << "seed " << seed << ": " << error->message();
      EXPECT_TRUE(error->fatal()) << "seed " << seed;
      EXPECT_FALSE(error->message().empty());
      ++errors;
    } else {
      EXPECT_FALSE(error.has_value()) << "seed " << seed << ": " << error->message();
    }
    EXPECT_TRUE(peer.wait_closed(3s)) << "seed " << seed;
  }
  // Both kinds of stream came up, so both branches above were taken.
  EXPECT_GT(errors, 0);
  EXPECT_LE(errors, 16);
  EXPECT_TRUE(eventually([&] { return server_->stats().dropped_total() >= 20u; }));
}

TEST_F(BadInput, RandomBytesAfterWelcomeEndOnlyThatSession) {
  start();
  RawPeer peer(server_->port());
  ASSERT_TRUE(peer.send(hello_message("garbage-after-hello")));
  auto welcome = peer.receive(3s);
  ASSERT_TRUE(welcome && welcome->has_welcome());
  const std::uint64_t body = welcome->welcome().body_id();
  // A frame of the right length whose bytes are not a ClientMessage: field 15 with
  // wire type 7 (invalid), then noise.
  std::string body_bytes = "\x7F\xFF\xFF\xFF\xFF\xFF\xFF\xFF\xFF\xFF\x01 noise";
  peer.send_bytes(varint(body_bytes.size()) + body_bytes);
  auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MALFORMED);
  EXPECT_TRUE(error->fatal());
  EXPECT_TRUE(peer.wait_closed(3s));
  EXPECT_TRUE(body_removed(body));
}

TEST_F(BadInput, LengthPrefixOverTheMaximumIsRefusedAndClosed) {
  start();
  RawPeer peer(server_->port());
  ASSERT_TRUE(peer.send(hello_message("too-large")));
  ASSERT_TRUE(peer.receive(3s).has_value());  // Welcome
  // One byte over the 1 MiB limit, and only the prefix: the server must refuse it
  // from the prefix alone, without waiting for (or allocating) the body.
  peer.send_bytes(varint(wire::kDefaultMaxMessageBytes + 1));
  auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MESSAGE_TOO_LARGE);
  EXPECT_TRUE(error->fatal());
  EXPECT_TRUE(peer.wait_closed(3s));
  EXPECT_TRUE(eventually(
      [&] { return dropped(server_->stats(), server::DropReason::MessageTooLarge) == 1; }));
}

TEST_F(BadInput, HugeLengthPrefixBeforeHelloIsRefused) {
  start();
  RawPeer peer(server_->port());
  peer.send_bytes(varint(std::numeric_limits<std::uint64_t>::max() / 2));
  auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_MESSAGE_TOO_LARGE);
  EXPECT_TRUE(peer.wait_closed(3s));
}

TEST_F(BadInput, OverlongVarintPrefixIsMalformed) {
  start();
  RawPeer peer(server_->port());
  peer.send_bytes(std::string(11, '\xFF'));
  auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  // PROTOCOL.md 1.1: a varint longer than 10 bytes is ERROR_MALFORMED, fatal.
  EXPECT_EQ(error->code(), pb::ERROR_MALFORMED) << error->message();
  EXPECT_TRUE(error->fatal());
  EXPECT_TRUE(peer.wait_closed(3s));
}

TEST_F(BadInput, FrameCutOffByADisconnectRemovesTheSession) {
  start();
  std::uint64_t body = 0;
  {
    RawPeer peer(server_->port());
    ASSERT_TRUE(peer.send(hello_message("cut-off")));
    auto welcome = peer.receive(3s);
    ASSERT_TRUE(welcome && welcome->has_welcome());
    body = welcome->welcome().body_id();
    // The prefix promises 50 bytes; 20 come, then the connection goes away.
    std::string partial = varint(50) + std::string(20, '\x08');
    peer.send_bytes(partial);
    peer.close();
  }
  EXPECT_TRUE(body_removed(body));
  EXPECT_TRUE(
      eventually([&] { return dropped(server_->stats(), server::DropReason::Disconnected) == 1; }));
}

TEST_F(BadInput, WrongTokenIsRefused) {
  server::ServerConfig config = test_config();
  config.token = "sesame";
  start(config);
  for (const std::string token : {"wrong", ""}) {
    client::ClientConfig intruder = server_->client_config("intruder");
    intruder.token = token;
    client::Client client(intruder);
    EXPECT_FALSE(client.connect(3s));
    EXPECT_EQ(client.state(), client::ConnectionState::Refused);
    ASSERT_TRUE(client.last_error().server.has_value()) << client.last_error().to_string();
    EXPECT_EQ(client.last_error().server->code, client::ErrorCode::BadToken);
    EXPECT_TRUE(client.last_error().server->fatal);
  }
  EXPECT_TRUE(
      eventually([&] { return dropped(server_->stats(), server::DropReason::BadToken) == 2; }));
}

TEST_F(BadInput, WrongProtocolVersionIsRefusedNamingBothVersions) {
  start();
  client::ClientConfig config = server_->client_config("from-the-future");
  config.protocol_version = 99;
  client::Client client(config);
  EXPECT_FALSE(client.connect(3s));
  EXPECT_EQ(client.state(), client::ConnectionState::Refused);
  ASSERT_TRUE(client.last_error().server.has_value()) << client.last_error().to_string();
  const client::ServerError& error = *client.last_error().server;
  EXPECT_EQ(error.code, client::ErrorCode::ProtocolVersion);
  EXPECT_NE(error.message.find("99"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find(std::to_string(client::kProtocolVersion)), std::string::npos)
      << error.message;
}

TEST_F(BadInput, NanAndInfiniteAccelerationAreRefusedAndTheSessionStays) {
  start();
  client::Client player(server_->client_config("nan"));
  ASSERT_TRUE(player.connect(3s));
  const std::uint64_t tick = player.welcome().current_tick + 2;
  ASSERT_TRUE(player.send_input(tick, std::nan(""), 0.0));
  ASSERT_TRUE(player.send_input(tick + 1, 0.0, std::numeric_limits<double>::infinity()));
  for (int i = 0; i < 2; ++i) {
    auto error = player.next_error(3s);
    ASSERT_TRUE(error.has_value()) << player.last_error().to_string();
    EXPECT_EQ(error->code, client::ErrorCode::InvalidInput);
    EXPECT_FALSE(error->fatal);
  }
  EXPECT_EQ(player.state(), client::ConnectionState::Connected);
  EXPECT_EQ(server_->stats().invalid_inputs, 2u);
  // Snapshots keep coming, the refused inputs were never applied, and the body is finite.
  auto later =
      player.wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.tick > tick + 2; });
  ASSERT_TRUE(later.has_value());
  EXPECT_FALSE(later->has_applied_input);
  ASSERT_TRUE(later->own.has_value());
  EXPECT_TRUE(std::isfinite(later->own->position.x) && std::isfinite(later->own->position.y));
  // A good input afterwards is applied.
  const std::uint64_t good = later->tick + 2;
  ASSERT_TRUE(player.send_input(good, 1.0, 0.0));
  EXPECT_TRUE(player
                  .wait_for_snapshot(3s,
                                     [&](const client::Snapshot& s) {
                                       return s.has_applied_input &&
                                              s.last_applied_input_tick >= good;
                                     })
                  .has_value());
}

TEST_F(BadInput, InputForAFarFutureTickIsRefused) {
  start();
  client::Client player(server_->client_config("far-future"));
  ASSERT_TRUE(player.connect(3s));
  const std::uint64_t now = player.welcome().current_tick;
  const std::uint64_t ahead = player.welcome().max_ticks_ahead;
  ASSERT_GT(ahead, 0u);
  ASSERT_TRUE(player.send_input(now + ahead + 1000, 40.0, 0.0));
  ASSERT_TRUE(player.send_input(std::numeric_limits<std::uint64_t>::max(), 40.0, 0.0));
  for (int i = 0; i < 2; ++i) {
    auto error = player.next_error(3s);
    ASSERT_TRUE(error.has_value()) << player.last_error().to_string();
    EXPECT_EQ(error->code, client::ErrorCode::TickTooFarAhead);
    EXPECT_FALSE(error->fatal);
  }
  EXPECT_EQ(player.state(), client::ConnectionState::Connected);
  EXPECT_EQ(server_->stats().far_future_inputs, 2u);
  auto later =
      player.wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.tick > now + 3; });
  ASSERT_TRUE(later.has_value());
  EXPECT_FALSE(later->has_applied_input);  // neither input was filed for later
}

TEST_F(BadInput, InputBeforeHelloIsAnUnexpectedMessage) {
  start();
  RawPeer peer(server_->port());
  ASSERT_TRUE(peer.send(input_message(1, 1.0, 1.0)));
  auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_UNEXPECTED_MESSAGE);
  EXPECT_TRUE(error->fatal());
  EXPECT_TRUE(peer.wait_closed(3s));
}

// PROTOCOL.md 3.1: anything but Hello first is ERROR_UNEXPECTED_MESSAGE, fatal; a
// Ping is no exception (it would keep a connection that never joined alive).
TEST_F(BadInput, PingAckOrFullStateRequestBeforeHelloAreUnexpected) {
  start();
  std::vector<pb::ClientMessage> firsts(3);
  firsts[0].mutable_ping()->set_nonce(1);
  firsts[1].mutable_ack()->set_tick(1);
  firsts[2].mutable_full_state_request();
  for (const pb::ClientMessage& first : firsts) {
    RawPeer peer(server_->port());
    ASSERT_TRUE(peer.send(first));
    auto error = peer.receive_error(3s);
    ASSERT_TRUE(error.has_value()) << first.ShortDebugString();
    EXPECT_EQ(error->code(), pb::ERROR_UNEXPECTED_MESSAGE) << first.ShortDebugString();
    EXPECT_TRUE(error->fatal());
    EXPECT_TRUE(peer.wait_closed(3s));
  }
}

TEST_F(BadInput, SecondHelloIsAnUnexpectedMessage) {
  start();
  RawPeer peer(server_->port());
  ASSERT_TRUE(peer.send(hello_message("twice")));
  auto welcome = peer.receive(3s);
  ASSERT_TRUE(welcome && welcome->has_welcome());
  ASSERT_TRUE(peer.send(hello_message("twice")));
  auto error = peer.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  // PROTOCOL.md 3.1: a second Hello is ERROR_UNEXPECTED_MESSAGE, fatal.
  EXPECT_EQ(error->code(), pb::ERROR_UNEXPECTED_MESSAGE);
  EXPECT_TRUE(error->fatal());
  EXPECT_TRUE(peer.wait_closed(3s));
}

TEST_F(BadInput, MaxClientsReachedRefusesTheNextOne) {
  server::ServerConfig config = test_config();
  config.max_clients = 2;  // the bystander and one more
  start(config);
  client::Client second(server_->client_config("second"));
  ASSERT_TRUE(second.connect(3s)) << second.last_error().to_string();
  client::Client third(server_->client_config("third"));
  EXPECT_FALSE(third.connect(3s));
  EXPECT_EQ(third.state(), client::ConnectionState::Refused);
  ASSERT_TRUE(third.last_error().server.has_value());
  EXPECT_EQ(third.last_error().server->code, client::ErrorCode::ServerFull);
  // When one leaves, there is room again (check_server_serves in TearDown joins).
  second.disconnect("making room");
  EXPECT_TRUE(eventually([&] { return server_->stats().connected_clients == 1; }));
}

// No message a client can send moves any body but its own: in a scene without
// gravity every other body stays exactly where it was, however hostile the inputs.
TEST_F(BadInput, NoMessageMovesAnyBodyButTheSendersOwn) {
  scene::SceneDef scene = crowd_scene(20);
  start(test_config(), scene);
  auto before = bystander_->newest_snapshot(3s);
  ASSERT_TRUE(before.has_value());

  client::Client attacker(server_->client_config("attacker"));
  ASSERT_TRUE(attacker.connect(3s));
  const std::uint64_t now = attacker.welcome().current_tick;
  const double huge = std::numeric_limits<double>::max();
  attacker.send_input(now + 1, huge, -huge);
  attacker.send_input(now + 2, std::nan(""), 1.0);
  attacker.send_input(now + 3, -1e300, 1e300);
  attacker.send_input(0, 40.0, 40.0);  // a tick long past
  attacker.send_input(now + 4, 50.0, 50.0);
  auto moved = attacker.wait_for_snapshot(3s, [&](const client::Snapshot& s) {
    return s.has_applied_input && s.last_applied_input_tick >= now + 4 && s.tick > now + 10;
  });
  ASSERT_TRUE(moved.has_value()) << attacker.last_error().to_string();
  ASSERT_TRUE(moved->own.has_value());
  EXPECT_GT(std::abs(moved->own->velocity.x), 0.0);  // its own body did move
  EXPECT_TRUE(std::isfinite(moved->own->position.x));

  auto after = bystander_->wait_for_snapshot(
      3s, [&](const client::Snapshot& s) { return s.tick >= moved->tick; });
  ASSERT_TRUE(after.has_value());
  std::size_t compared = 0;
  for (const client::BodyState& body : before->bodies) {
    const client::BodyState* now_state = after->find(body.body_id);
    ASSERT_NE(now_state, nullptr) << "body " << body.body_id << " vanished";
    EXPECT_EQ(now_state->position, body.position) << "body " << body.body_id;
    EXPECT_EQ(now_state->velocity, body.velocity) << "body " << body.body_id;
    ++compared;
  }
  EXPECT_GE(compared, 21u);  // the crowd and the bystander
  EXPECT_EQ(before->find(attacker.welcome().body_id), nullptr);
  EXPECT_GE(server_->stats().clamped_inputs, 1u);
  attacker.disconnect();
}

// Every view setting out of range is refused with ERROR_INVALID_VIEW, naming the
// field, and the session is closed; the others are served on (TearDown).
TEST_F(BadInput, ViewSettingsOutOfRangeAreRefusedNamingTheField) {
  start();
  struct Case {
    const char* field;
    std::function<void(pb::ViewRequest&)> set;
  };
  const std::vector<Case> cases = {
      {"position_precision", [](pb::ViewRequest& v) { v.set_position_precision(0.0); }},
      {"position_precision", [](pb::ViewRequest& v) { v.set_position_precision(-0.001); }},
      {"velocity_precision", [](pb::ViewRequest& v) { v.set_velocity_precision(std::nan("")); }},
      {"position_tolerance", [](pb::ViewRequest& v) { v.set_position_tolerance(1e-6); }},
      {"snapshot_interval", [](pb::ViewRequest& v) { v.set_snapshot_interval(0); }},
      {"snapshot_interval", [](pb::ViewRequest& v) { v.set_snapshot_interval(1000000000); }},
      {"window", [](pb::ViewRequest& v) { v.set_window(0); }},
      {"interest_radius", [](pb::ViewRequest& v) { v.set_interest_radius(1e308); }},
      {"interest_radius", [](pb::ViewRequest& v) { v.set_interest_radius(-1.0); }},
      {"interest_rect", [](pb::ViewRequest& v) { v.mutable_interest_rect()->set_max_x(-1.0); }},
      {"byte_budget", [](pb::ViewRequest& v) { v.set_byte_budget(3); }},
      {"encoding", [](pb::ViewRequest& v) { v.set_encoding(static_cast<pb::Encoding>(9)); }},
  };
  for (const Case& c : cases) {
    RawPeer peer(server_->port());
    pb::ClientMessage hello = hello_message("bad-view");
    c.set(*hello.mutable_hello()->mutable_view());
    ASSERT_TRUE(peer.send(hello));
    auto error = peer.receive_error(3s);
    ASSERT_TRUE(error.has_value()) << c.field;
    EXPECT_EQ(error->code(), pb::ERROR_INVALID_VIEW) << c.field;
    EXPECT_TRUE(error->fatal()) << c.field;
    EXPECT_NE(error->message().find(c.field), std::string::npos) << error->message();
    EXPECT_TRUE(peer.wait_closed(3s)) << c.field;
  }
}

// Acks for ticks never sent, a flood of acks, and a full-state request every tick:
// non-fatal Errors where the protocol says so, and the session goes on.
TEST_F(BadInput, BadAcksFloodsOfAcksAndFullStateRequestsKeepTheSession) {
  start();
  client::Client peer(server_->client_config("acker"));
  ASSERT_TRUE(peer.connect(3s)) << peer.last_error().to_string();
  auto first = peer.next_snapshot(3s);
  ASSERT_TRUE(first.has_value());
  RawPeer raw(server_->port());
  ASSERT_TRUE(raw.send(hello_message("raw-acker")));
  auto welcome = raw.receive(3s);
  ASSERT_TRUE(welcome && welcome->has_welcome());
  pb::ClientMessage ack;
  ack.mutable_ack()->set_tick(welcome->welcome().current_tick() + 1000000);
  ASSERT_TRUE(raw.send(ack));
  auto error = raw.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), pb::ERROR_INVALID_ACK);
  EXPECT_FALSE(error->fatal());
  // A flood of acks of a tick it was sent: each harmless and silent.
  std::optional<pb::ServerMessage> got;
  do {
    got = raw.receive(3s);
  } while (got && !got->has_snapshot());
  ASSERT_TRUE(got.has_value());
  ack.mutable_ack()->set_tick(got->snapshot().tick());
  std::string flood;
  for (int i = 0; i < 5000; ++i) flood += wire::encode_frame(ack);
  ASSERT_TRUE(raw.send_bytes(flood));
  // A full-state request every tick for a second: served or merged, some refused.
  pb::ClientMessage request;
  request.mutable_full_state_request();
  std::uint64_t rate_limited = 0;
  for (int i = 0; i < 60; ++i) {
    ASSERT_TRUE(raw.send(request));
    ASSERT_TRUE(raw.send(request));
    if (auto e = raw.receive_error(100ms)) {
      EXPECT_EQ(e->code(), pb::ERROR_RATE_LIMITED);
      EXPECT_FALSE(e->fatal());
      ++rate_limited;
    }
  }
  EXPECT_GT(rate_limited, 0u);
  EXPECT_GE(server_->stats().full_states, 2u);
  EXPECT_FALSE(raw.closed());
  raw.close();
  // The well-behaved client is still in sync with the server's mirror of it.
  auto later =
      peer.wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.tick > first->tick; });
  ASSERT_TRUE(later.has_value());
  EXPECT_TRUE(later->in_sync);
  EXPECT_EQ(peer.stats().desyncs, 0u);
  peer.disconnect();
}

}  // namespace
}  // namespace itest
