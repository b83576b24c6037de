// What a live Client writes to its socket, read by a stand-in server on loopback with
// the server's own parser: the Hello its config asks for, Inputs numbered from 1, the
// Ack of a snapshot taken, and Bye.
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

}  // namespace
