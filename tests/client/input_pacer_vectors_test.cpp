// The input pacer against tests/vectors/input_pacer.json, as the TypeScript client's
// InputPacer (client/web/client/test/input_pacer_vectors.test.mjs): PacerConfig's
// defaults, and the clock a pacer makes from its config and the server's Welcome. The
// pacer needs a connected Client: a stand-in server on loopback answers its Hello with
// the case's Welcome. (The file's schedules run in TypeScript only: the C++ pacer reads
// the steady clock itself.)
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <utility>

#include "client/client.h"
#include "client/input_pacer.h"
#include "vectors.h"
#include "wire.pb.h"
#include "wire/framing.h"
#include "wire/messages.h"

namespace {

namespace pb = physics::wire;
using namespace std::chrono_literals;
using nlohmann::json;

// One connection on a free loopback port: reads until the client's Hello has arrived
// (any bytes), answers with `welcome`, then holds the connection until the client
// closes it. Reads give up after 10 s, so a broken client fails instead of hanging.
class WelcomingStandIn {
 public:
  explicit WelcomingStandIn(pb::ServerMessage welcome) : welcome_(std::move(welcome)) {
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
    thread_ = std::jthread([this] { serve(); });
  }
  ~WelcomingStandIn() {
    thread_ = {};  // joined: the client has closed by now
    ::close(listener_);
  }
  std::uint16_t port() const { return port_; }

 private:
  void serve() {
    const int peer = ::accept(listener_, nullptr, nullptr);
    if (peer < 0) return;
    timeval timeout{10, 0};
    ::setsockopt(peer, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    char buffer[4096];
    if (::recv(peer, buffer, sizeof buffer, 0) > 0) {
      const std::string frame = wire::encode_frame(welcome_);
      ::send(peer, frame.data(), frame.size(), MSG_NOSIGNAL);
      while (::recv(peer, buffer, sizeof buffer, 0) > 0) {
      }
    }
    ::close(peer);
  }

  pb::ServerMessage welcome_;
  int listener_ = -1;
  std::uint16_t port_ = 0;
  std::jthread thread_;
};

pb::ServerMessage welcome_of(const json& welcome) {
  pb::ServerMessage message;
  pb::Welcome& w = *message.mutable_welcome();
  w.set_protocol_version(wire::kProtocolVersion);
  w.set_client_id(1);
  w.set_body_id(1);
  w.set_tick_rate(welcome["tick_rate"].get<double>());
  w.set_max_ticks_ahead(welcome["max_ticks_ahead"].get<std::uint32_t>());
  // Lockstep: the pacer's clock waits at the current tick instead of reading the clock.
  w.set_lockstep(true);
  w.set_current_tick(10);
  w.mutable_view()->set_encoding(pb::ENCODING_FULL);
  return message;
}

TEST(InputPacerVectors, TheDefaultConfigIsTheVectors) {
  const json vectors = vectors::load("input_pacer");
  const json& want = vectors["defaults"];
  const client::PacerConfig defaults;
  EXPECT_EQ(defaults.schedule, client::InputSchedule::Clock);
  EXPECT_EQ(want["schedule"].get<std::string>(), "clock");
  EXPECT_EQ(defaults.after_snapshot_lead, want["after_snapshot_lead"].get<std::uint64_t>());
  EXPECT_EQ(defaults.ping_interval.count(), want["ping_interval_ms"].get<std::int64_t>());
  EXPECT_EQ(defaults.clock.tick_rate, want["clock_tick_rate"].get<double>());
}

TEST(InputPacerVectors, TheClockTakesTheWelcomesTickRateAndStaysBelowItsMaxTicksAhead) {
  const json vectors = vectors::load("input_pacer");
  ASSERT_FALSE(vectors["clock_from_welcome"].empty());
  for (const json& vector : vectors["clock_from_welcome"]) {
    SCOPED_TRACE(vector["name"].get<std::string>());
    WelcomingStandIn server(welcome_of(vector["welcome"]));
    client::ClientConfig config;
    config.port = server.port();
    config.keepalive = 0ms;
    client::Client client(config);
    ASSERT_TRUE(client.connect(5s)) << client.last_error().to_string();

    client::PacerConfig pacer_config;
    const json& clock = vector["clock"];
    pacer_config.clock.fixed_delay = clock["fixed_delay"].get<std::uint32_t>();
    if (clock.contains("tick_rate"))
      pacer_config.clock.tick_rate = clock["tick_rate"].get<double>();
    if (clock.contains("max_delay"))
      pacer_config.clock.max_delay = clock["max_delay"].get<std::uint32_t>();
    const client::InputPacer pacer(client, pacer_config);
    EXPECT_NEAR(static_cast<double>(pacer.clock().period().count()) / 1e6,
                vector["period_ms"].get<double>(), 1e-5);
    EXPECT_EQ(pacer.clock().delay(), vector["delay"].get<std::uint32_t>());
    client.disconnect("done");
  }
}

}  // namespace
