// What a live Client writes to its socket, read by a stand-in server on loopback with
// the server's own parser: the Hello its config asks for, Inputs numbered from 1, the
// Ack of a snapshot taken, and Bye; and a client out of sync asking for a full state.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "client/client.h"
#include "convert.h"
#include "wire.pb.h"
#include "wire/framing.h"
#include "wire/messages.h"
#include "wire/predictor.h"
#include "wire/reconstruction.h"

namespace {

namespace pb = physics::wire;
using namespace std::chrono_literals;

// A listening socket on 127.0.0.1 with a free port; one connection, blocking reads
// that give up after 10 s so that a broken client fails the test instead of hanging.
class StandIn {
 public:
  StandIn() {
    listener_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    if (::bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
        ::listen(listener_, 1) != 0 ||
        ::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
      ADD_FAILURE() << "cannot listen on loopback";
    }
    port_ = ntohs(address.sin_port);
  }
  ~StandIn() {
    if (peer_ >= 0) ::close(peer_);
    ::close(listener_);
  }
  std::uint16_t port() const { return port_; }

  bool accept() {
    peer_ = ::accept(listener_, nullptr, nullptr);
    if (peer_ < 0) return false;
    timeval timeout{10, 0};
    ::setsockopt(peer_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    return true;
  }

  // The next message the client sent; nullopt when the connection ended first.
  std::optional<pb::ClientMessage> next() {
    std::string frame;
    while (reader_.next(frame) != wire::FrameStatus::Frame) {
      std::uint8_t buffer[4096];
      const ssize_t got = ::recv(peer_, buffer, sizeof buffer, 0);
      if (got <= 0) return std::nullopt;
      reader_.feed(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(got)));
    }
    pb::ClientMessage message;
    if (!wire::parse_client_message(frame, message)) return std::nullopt;
    return message;
  }

  void send(const pb::ServerMessage& message) {
    const std::string frame = wire::encode_frame(message);
    EXPECT_EQ(::send(peer_, frame.data(), frame.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(frame.size()));
  }

 private:
  int listener_ = -1;
  int peer_ = -1;
  std::uint16_t port_ = 0;
  wire::FrameReader reader_;
};

pb::ServerMessage welcome() {
  pb::ServerMessage message;
  pb::Welcome& w = *message.mutable_welcome();
  w.set_protocol_version(wire::kProtocolVersion);
  w.set_client_id(1);
  w.set_body_id(1);
  w.set_tick_rate(60.0);
  w.set_current_tick(10);
  w.mutable_view()->set_encoding(pb::ENCODING_FULL);
  w.mutable_view()->set_window(12);
  return message;
}

pb::ServerMessage snapshot(std::uint64_t tick) {
  pb::ServerMessage message;
  message.mutable_snapshot()->set_tick(tick);
  return message;
}

TEST(ClientWire, TheClientSendsItsHelloInputsAckAndByeAsSharedWireBuildsThem) {
  StandIn server;
  client::ClientConfig config;
  config.port = server.port();
  config.name = "ann";
  config.seat = 2;
  config.keepalive = 0ms;  // no Pings in between: the messages are exactly these
  std::vector<pb::ClientMessage> received;
  std::jthread stand_in([&] {  // joined on every way out of the test
    if (!server.accept()) return;
    std::optional<pb::ClientMessage> message = server.next();
    if (!message) return;
    received.push_back(*message);
    server.send(welcome());
    server.send(snapshot(11));
    while ((message = server.next())) received.push_back(*message);
  });

  client::Client client(config);
  ASSERT_TRUE(client.connect(5s)) << client.last_error().to_string();
  ASSERT_TRUE(client.next_snapshot(5s).has_value());  // taken: acknowledged with the input
  EXPECT_TRUE(client.send_input(11, 1.5, 0.0));
  EXPECT_TRUE(client.send_input(12, 0.0, -2.0));
  client.disconnect("done");
  stand_in.join();

  ASSERT_EQ(received.size(), 5u);
  ASSERT_TRUE(received[0].has_hello());
  EXPECT_EQ(received[0].SerializeAsString(),
            client::convert::make_hello(config).SerializeAsString());
  EXPECT_EQ(received[0].hello().seat(), 2u);
  EXPECT_FALSE(received[0].hello().has_view());
  ASSERT_TRUE(received[1].has_ack());
  EXPECT_EQ(received[1].ack().tick(), 11u);
  ASSERT_TRUE(received[2].has_input());
  EXPECT_EQ(received[2].SerializeAsString(), wire::make_input(11, 1.5, 0.0, 1).SerializeAsString());
  ASSERT_TRUE(received[3].has_input());
  EXPECT_EQ(received[3].input().sequence(), 2u);
  EXPECT_EQ(received[3].input().ay(), -2.0);
  ASSERT_TRUE(received[4].has_bye());
  EXPECT_EQ(received[4].bye().reason(), "done");
}

// One body, 5, sent as a quantised record against what the client holds; the view
// hash is what a client that applied every record faithfully holds after it.
pb::ServerMessage snapshot_of_body(std::uint64_t tick, bool full, std::int64_t dx,
                                   wire::Reconstruction& truth, std::int64_t dx_sent) {
  const wire::Predictor predictor(60.0, 0.0, 0.0);
  pb::ServerMessage message;
  pb::Snapshot& s = *message.mutable_snapshot();
  s.set_tick(tick);
  s.set_full(full);
  pb::QuantizedBodies& q = *s.mutable_quantized();
  q.add_id_gaps(5);
  q.add_dx(dx);
  q.add_dy(0);
  q.add_dvx(0);
  q.add_dvy(0);
  EXPECT_EQ(truth.apply(s, predictor, {}), "");
  s.set_view_hash(truth.hash());
  q.set_dx(0, dx_sent);  // what goes on the wire: corrupted when dx_sent != dx
  return message;
}

// A snapshot whose record was corrupted on the way: the client's hash differs from
// the server's, so it marks itself out of sync, asks for a full state (once), and
// is in sync again after the full state; a later snapshot without a hash keeps that.
TEST(ClientWire, AClientOutOfSyncAsksForAFullStateAndIsInSyncAfterIt) {
  StandIn server;
  client::ClientConfig config;
  config.port = server.port();
  bool asked = false;
  std::jthread stand_in([&] {
    if (!server.accept() || !server.next()) return;
    pb::ServerMessage hello_answer = welcome();
    hello_answer.mutable_welcome()->mutable_view()->set_encoding(pb::ENCODING_PREDICTED);
    hello_answer.mutable_welcome()->mutable_view()->set_position_precision(0.001);
    hello_answer.mutable_welcome()->mutable_view()->set_velocity_precision(0.001);
    server.send(hello_answer);
    wire::Reconstruction truth;
    server.send(snapshot_of_body(11, true, 1000, truth, 1000));
    server.send(snapshot_of_body(12, false, 3, truth, 4));
    std::optional<pb::ClientMessage> message;
    while ((message = server.next())) {
      if (message->has_full_state_request()) {
        asked = true;
        break;
      }
    }
    if (!asked) return;
    server.send(snapshot_of_body(13, true, 2000, truth, 2000));
    pb::ServerMessage header = snapshot(14);
    server.send(header);
    while ((message = server.next())) {
      if (message->has_full_state_request()) asked = false;  // a second request: wrong
    }
  });

  client::Client client(config);
  ASSERT_TRUE(client.connect(5s)) << client.last_error().to_string();
  const auto first = client.next_snapshot(5s);
  ASSERT_TRUE(first.has_value());
  EXPECT_TRUE(first->in_sync);
  const auto corrupted = client.next_snapshot(5s);
  ASSERT_TRUE(corrupted.has_value());
  EXPECT_EQ(corrupted->tick, 12u);
  EXPECT_FALSE(corrupted->in_sync);
  EXPECT_EQ(client.stats().desyncs, 1u);
  const auto full = client.next_snapshot(5s);
  ASSERT_TRUE(full.has_value());
  EXPECT_EQ(full->tick, 13u);
  EXPECT_TRUE(full->in_sync);
  ASSERT_EQ(full->bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(full->bodies[0].position.x, 2.0);
  const auto header = client.next_snapshot(5s);
  ASSERT_TRUE(header.has_value());
  EXPECT_EQ(header->tick, 14u);
  EXPECT_TRUE(header->in_sync);
  EXPECT_EQ(client.stats().desyncs, 1u);
  EXPECT_EQ(client.stats().full_states_received, 2u);
  client.disconnect("done");
  stand_in.join();
  EXPECT_TRUE(asked) << "the client never sent a FullStateRequest";
}

}  // namespace
