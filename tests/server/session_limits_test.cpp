// One Session over a real loopback socket, with a host of the test's own: a burst of
// Pings waits for its Pongs instead of getting the client dropped, a flood over the
// message rate pauses reading (and is counted) instead of costing us without bound,
// and a handler that throws closes its own session with ERROR_INTERNAL while the
// others go on.
#include <gtest/gtest.h>

#include <asio.hpp>
#include <chrono>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "session.h"
#include "wire.pb.h"
#include "wire/framing.h"

namespace {

using namespace std::chrono_literals;
namespace pb = physics::wire;

// Answers Ping with Pong, like the server; throws for a Ping whose nonce is kThrow.
class TestHost final : public server::SessionHost {
 public:
  static constexpr std::uint64_t kThrow = std::uint64_t{1} << 40;  // no burst reaches it

  void on_message(server::Session& session, pb::ClientMessage& message) override {
    ++handled;
    if (!message.has_ping()) return;
    if (message.ping().nonce() == kThrow) throw std::bad_alloc();
    pb::ServerMessage reply;
    reply.mutable_pong()->set_nonce(message.ping().nonce());
    session.send(reply);
  }
  void on_closed(server::Session& /*session*/, server::DropReason reason) override {
    closed.push_back(reason);
  }
  void on_bytes(std::size_t /*sent*/, std::size_t /*received*/) override {}
  void on_throttled(server::Session& /*session*/) override { ++throttled; }
  void on_handler_failed(server::Session& /*session*/, const char* what) override {
    failures.emplace_back(what);
  }

  std::size_t handled = 0;
  std::size_t throttled = 0;
  std::vector<server::DropReason> closed;
  std::vector<std::string> failures;
};

// A client socket and the server's Session for it, both on the test's io_context.
struct Pair {
  asio::ip::tcp::socket client;
  std::shared_ptr<server::Session> session;
};

class SessionLimits : public ::testing::Test {
 protected:
  Pair connect(std::uint32_t id, server::SessionLimits limits) {
    asio::ip::tcp::socket client(io_);
    client.connect(acceptor_.local_endpoint());
    asio::ip::tcp::socket accepted(io_);
    acceptor_.accept(accepted);
    auto session = std::make_shared<server::Session>(std::move(accepted), id, host_, limits);
    session->set_joined("test");
    session->start();
    return {std::move(client), std::move(session)};
  }

  // Runs the io_context until `done` or the timeout.
  bool run_until(const std::function<bool()>& done, std::chrono::milliseconds timeout = 5s) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!done()) {
      if (std::chrono::steady_clock::now() >= deadline) return false;
      io_.run_for(5ms);
      if (io_.stopped()) io_.restart();
    }
    return true;
  }

  // Reads what the client has been sent, into `reader`, without blocking.
  void drain(asio::ip::tcp::socket& client, wire::FrameReader& reader) {
    std::error_code ec;
    client.non_blocking(true, ec);
    std::array<std::uint8_t, 65536> buffer{};
    for (;;) {
      const std::size_t n = client.read_some(asio::buffer(buffer), ec);
      if (ec) return;
      reader.feed(std::span<const std::uint8_t>(buffer.data(), n));
    }
  }

  asio::io_context io_;
  asio::ip::tcp::acceptor acceptor_{io_, {asio::ip::make_address("127.0.0.1"), 0}};
  TestHost host_;
};

std::string pings(int count, std::uint64_t first_nonce = 1) {
  std::string bytes;
  for (int i = 0; i < count; ++i) {
    pb::ClientMessage ping;
    ping.mutable_ping()->set_nonce(first_nonce + static_cast<std::uint64_t>(i));
    bytes += wire::encode_frame(ping);
  }
  return bytes;
}

TEST_F(SessionLimits, ABurstOfPingsIsAnsweredInFullAndNeverDropsTheClient) {
  server::SessionLimits limits;  // the defaults: at most 256 control messages queued
  Pair pair = connect(1, limits);
  constexpr int kBurst = 5000;  // far over the queue's 256, in one write
  asio::write(pair.client, asio::buffer(pings(kBurst)));
  wire::FrameReader reader;
  std::size_t pongs = 0;
  std::string frame;
  ASSERT_TRUE(run_until([&] {
    drain(pair.client, reader);
    while (reader.next(frame) == wire::FrameStatus::Frame) {
      pb::ServerMessage message;
      EXPECT_TRUE(message.ParseFromString(frame));
      EXPECT_TRUE(message.has_pong());
      EXPECT_EQ(message.pong().nonce(), pongs + 1);  // in order, none lost
      ++pongs;
    }
    return pongs == kBurst;
  })) << pongs
      << " pongs";
  EXPECT_TRUE(host_.closed.empty());
  EXPECT_FALSE(pair.session->closing());
  EXPECT_LE(pair.session->queued_messages(), limits.pause_reading_at_control + 1);
  EXPECT_EQ(host_.throttled, 0u);  // within the message rate: never paused for it
}

TEST_F(SessionLimits, AFloodOverTheMessageRateIsPausedNotDropped) {
  server::SessionLimits limits;
  limits.messages_per_second = 2000;
  limits.message_burst = 500;
  Pair pair = connect(1, limits);
  // 1500 acks (no reply): the burst, then a second of the rate for the rest.
  std::string flood;
  pb::ClientMessage ack;
  ack.mutable_ack()->set_tick(1);
  for (int i = 0; i < 1500; ++i) flood += wire::encode_frame(ack);
  asio::write(pair.client, asio::buffer(flood));
  // Soon after the write the burst is handled and the rest waits.
  ASSERT_TRUE(run_until([&] { return host_.handled >= 500; }));
  EXPECT_LT(host_.handled, 1500u);
  EXPECT_GT(host_.throttled, 0u);
  // And all of it is handled in the end, the session still open.
  ASSERT_TRUE(run_until([&] { return host_.handled == 1500; }));
  EXPECT_TRUE(host_.closed.empty());
}

TEST_F(SessionLimits, AHandlerThatThrowsClosesItsSessionOnly) {
  server::SessionLimits limits;
  Pair faulty = connect(1, limits);
  Pair healthy = connect(2, limits);
  asio::write(faulty.client, asio::buffer(pings(1, TestHost::kThrow)));
  wire::FrameReader reader;
  std::string frame;
  std::optional<pb::Error> error;
  ASSERT_TRUE(run_until([&] {
    drain(faulty.client, reader);
    while (reader.next(frame) == wire::FrameStatus::Frame) {
      pb::ServerMessage message;
      if (message.ParseFromString(frame) && message.has_error()) error = message.error();
    }
    return error.has_value();
  }));
  EXPECT_EQ(error->code(), pb::ERROR_INTERNAL);
  EXPECT_TRUE(error->fatal());
  ASSERT_EQ(host_.failures.size(), 1u);
  faulty.client.close();
  ASSERT_TRUE(run_until([&] { return !host_.closed.empty(); }));
  EXPECT_EQ(host_.closed.front(), server::DropReason::InternalError);
  // The other session is served as before.
  asio::write(healthy.client, asio::buffer(pings(1, 7)));
  wire::FrameReader healthy_reader;
  std::optional<pb::ServerMessage> pong;
  ASSERT_TRUE(run_until([&] {
    drain(healthy.client, healthy_reader);
    if (healthy_reader.next(frame) == wire::FrameStatus::Frame) {
      pong.emplace();
      EXPECT_TRUE(pong->ParseFromString(frame));
    }
    return pong.has_value();
  }));
  EXPECT_EQ(pong->pong().nonce(), 7u);
  EXPECT_FALSE(healthy.session->closing());
  EXPECT_EQ(host_.closed.size(), 1u);
}

}  // namespace
