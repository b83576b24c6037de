// Bad flow: well-formed messages at the wrong time or in the wrong number. Anything
// but Hello first, a second Hello and a client past max_clients are refused, fatal;
// acks of ticks never sent, floods of acks and full-state requests every tick get
// non-fatal answers, and the session goes on.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "bad_input_fixture.h"
#include "wire/framing.h"

namespace itest {
namespace {

namespace pb = physics::wire;

TEST_F(BadInput, InputBeforeHelloIsAnUnexpectedMessage) {
  start();
  RawPeer peer(server_->port());
  ASSERT_TRUE(peer.send(input_message(1, 1.0, 1.0)));
  EXPECT_TRUE(fatal_error_then_closed(peer, pb::ERROR_UNEXPECTED_MESSAGE));
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
  // PROTOCOL.md 3.1: a second Hello is ERROR_UNEXPECTED_MESSAGE, fatal.
  EXPECT_TRUE(fatal_error_then_closed(peer, pb::ERROR_UNEXPECTED_MESSAGE));
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
  EXPECT_TRUE(third.last_error().server->fatal);
  // The refusal cost the players nothing: the second is still served.
  EXPECT_TRUE(second.next_snapshot(3s).has_value()) << second.last_error().to_string();
  // When one leaves, there is room again (check_server_serves in TearDown joins).
  second.disconnect("making room");
  EXPECT_TRUE(eventually([&] { return server_->stats().connected_clients == 1; }));
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
