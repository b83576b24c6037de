// When the input relay is attached to the world (docs/PROTOCOL.md 5.12): only while
// a welcomed client follows it. A refused Hello that asked for the relay and the
// world leaves it detached and is sent no world; the last relay client leaving
// detaches it; a relay client welcomed after that follows the world bit for bit.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "harness.h"
#include "relay/follow_relay.h"

namespace itest {
namespace {

physics::wire::ClientMessage relay_hello(const std::string& name, const std::string& token) {
  physics::wire::ClientMessage message = hello_message(name, token);
  physics::wire::Hello& hello = *message.mutable_hello();
  hello.set_want_world(true);
  hello.mutable_view()->set_encoding(physics::wire::ENCODING_INPUTS);
  hello.mutable_view()->set_state_hash(true);
  hello.mutable_view()->set_window(64);
  return message;
}

server::ServerConfig config_with_token() {
  server::ServerConfig config = test_config();
  config.token = "right token";
  return config;
}

// Waits until the server has stepped `ticks` more ticks.
bool ticks_pass(const RunningServer& server, std::uint64_t ticks) {
  const std::uint64_t from = server.stats().ticks_stepped;
  return eventually([&] { return server.stats().ticks_stepped >= from + ticks; });
}

TEST(RelayAttach, ARefusedRelayHelloLeavesTheRelayDetached) {
  RunningServer server(config_with_token(), scene::default_scene());
  RawPeer peer(server.port());
  ASSERT_TRUE(peer.send(relay_hello("intruder", "wrong token")));
  const auto first = peer.receive(5s);
  ASSERT_TRUE(first.has_value());
  ASSERT_TRUE(first->has_error()) << "the refused Hello got something else first";
  EXPECT_EQ(first->error().code(), physics::wire::ERROR_BAD_TOKEN);
  EXPECT_TRUE(peer.wait_closed(5s));
  ASSERT_TRUE(ticks_pass(server, 10));
  const server::ServerStats stats = server.stats();
  EXPECT_EQ(stats.relay_clients, 0u);
  EXPECT_EQ(stats.relay_ticks_held, 0u) << "the relay logged ticks for nobody";
  EXPECT_EQ(stats.full_states, 0u);
}

// Follows relayed ticks from a Welcome; true once `ticks` were followed with the
// server's state hash matched after each.
std::string follow_ticks(RawPeer& peer, int ticks) {
  const auto welcome = peer.receive(5s);
  if (!welcome || !welcome->has_welcome()) return "no Welcome";
  std::string problem;
  std::optional<phys::World> world = relay::world_from(welcome->welcome().world_state(), &problem);
  if (!world) return problem;
  const double dt = 1.0 / welcome->welcome().tick_rate();
  int followed = 0;
  while (followed < ticks) {
    const auto message = peer.receive(5s);
    if (!message) return "no snapshot after " + std::to_string(followed) + " ticks";
    if (!message->has_snapshot()) continue;
    const physics::wire::Snapshot& s = message->snapshot();
    for (const physics::wire::RelayTick& t : s.relay()) {
      const relay::FollowResult result = relay::follow(*world, t, dt);
      if (result.problem != relay::FollowProblem::None) return result.detail;
      ++followed;
    }
    if (world->state_hash() != s.state_hash()) {
      return "the world differs from the server's at tick " + std::to_string(s.tick());
    }
    physics::wire::ClientMessage ack;
    ack.mutable_ack()->set_tick(s.tick());
    if (!peer.send(ack)) return "closed";
  }
  return {};
}

TEST(RelayAttach, TheLastRelayClientLeavingDetachesItAndANewOneFollows) {
  RunningServer server(config_with_token(), scene::default_scene());
  {
    RawPeer first(server.port());
    ASSERT_TRUE(first.send(relay_hello("first", "right token")));
    EXPECT_EQ(follow_ticks(first, 20), "");
    EXPECT_EQ(server.stats().relay_clients, 1u);
    EXPECT_GT(server.stats().relay_ticks_held, 0u);
  }
  ASSERT_TRUE(eventually([&] { return server.stats().relay_clients == 0; }));
  ASSERT_TRUE(ticks_pass(server, 5));
  EXPECT_EQ(server.stats().relay_ticks_held, 0u);

  // Attached again, from an empty log: its ticks follow on from the Welcome's world.
  RawPeer second(server.port());
  ASSERT_TRUE(second.send(relay_hello("second", "right token")));
  EXPECT_EQ(follow_ticks(second, 30), "");
  EXPECT_EQ(server.stats().relay_resyncs, 0u);
}

}  // namespace
}  // namespace itest
