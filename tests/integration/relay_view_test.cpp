// The input relay over a real server (docs/PROTOCOL.md 5.12), through a 30 ms
// one-way path: a client that asked for the world reads it from its Welcome,
// follows every relayed tick, and holds the server's world bit for bit at every
// tick (the world's state hash in every snapshot says so), while another player
// joins and leaves; its snapshots carry no body records; a FullStateRequest is
// answered with the world's state; and the relay without the world is refused.
#include <gtest/gtest.h>

#include <string>

#include "harness.h"
#include "physics_testing/link_conditioner.h"
#include "relay/follow_relay.h"
#include "wire/relay_ticks.h"

namespace itest {
namespace {

using physics_testing::LinkConditioner;

physics::wire::ClientMessage relay_hello(const std::string& name) {
  physics::wire::ClientMessage message = hello_message(name);
  physics::wire::Hello& hello = *message.mutable_hello();
  hello.set_want_world(true);
  hello.mutable_view()->set_encoding(physics::wire::ENCODING_INPUTS);
  hello.mutable_view()->set_state_hash(true);
  hello.mutable_view()->set_view_hash_interval(1);
  hello.mutable_view()->set_window(64);
  return message;
}

physics::wire::ClientMessage ack(std::uint64_t tick) {
  physics::wire::ClientMessage message;
  message.mutable_ack()->set_tick(tick);
  return message;
}

// A relay client: its world, and what it saw.
struct Follower {
  std::optional<phys::World> world;
  double dt = 0.0;
  std::uint64_t tick = 0;
  std::uint64_t followed = 0;
  std::uint64_t compared = 0;
  std::uint64_t body_records = 0;
  std::uint64_t world_states = 0;
  std::uint64_t numbered_on_the_wire = 0;  // relayed ticks that carried their number
  std::string problem;

  bool welcome(const physics::wire::Welcome& w) {
    dt = 1.0 / w.tick_rate();
    tick = w.current_tick();
    world = relay::world_from(w.world_state(), &problem);
    return world.has_value();
  }
  // Applies one snapshot; false on the first problem.
  bool apply(const physics::wire::Snapshot& s) {
    body_records += static_cast<std::uint64_t>(s.bodies_size() + s.added_size()) +
                    s.quantized().id_gaps_size() + s.exact().id_gaps_size() +
                    s.velocities().id_gaps_size();
    if (!s.world_state().empty()) {
      ++world_states;
      world = relay::world_from(s.world_state(), &problem);
      if (!world) return false;
      tick = s.tick();
    }
    // The server leaves the relayed ticks' numbers implied (PROTOCOL.md 5.12).
    for (const physics::wire::RelayTick& t : s.relay()) numbered_on_the_wire += t.tick() != 0;
    physics::wire::Snapshot numbered = s;
    wire::number_relay_ticks(numbered);
    for (const physics::wire::RelayTick& t : numbered.relay()) {
      if (t.tick() != tick + 1) {
        problem = "relay tick " + std::to_string(t.tick()) + " after " + std::to_string(tick);
        return false;
      }
      const relay::FollowResult result = relay::follow(*world, t, dt);
      if (result.problem != relay::FollowProblem::None) {
        problem = result.detail;
        return false;
      }
      tick = t.tick();
      ++followed;
    }
    if (tick != s.tick()) {
      problem = "a snapshot of tick " + std::to_string(s.tick()) + " left the world at " +
                std::to_string(tick);
      return false;
    }
    if (world->state_hash() != s.state_hash()) {
      problem = "the world differs from the server's after tick " + std::to_string(s.tick());
      return false;
    }
    ++compared;
    return true;
  }
};

TEST(RelayView, AFollowerHoldsTheServersWorldThroughAPath) {
  RunningServer server(test_config(), scene::default_scene());
  LinkConditioner link(
      physics_testing::relay_to(server.port(), physics_testing::symmetric_path(30ms)));
  RawPeer peer(link.port());
  ASSERT_TRUE(peer.send(relay_hello("follower")));
  const auto welcome = peer.receive(5s);
  ASSERT_TRUE(welcome && welcome->has_welcome());
  Follower follower;
  ASSERT_TRUE(follower.welcome(welcome->welcome())) << follower.problem;

  std::unique_ptr<RawPeer> other;
  for (int n = 0; n < 240; ++n) {
    const auto message = peer.receive(5s);
    ASSERT_TRUE(message.has_value()) << "snapshot " << n;
    if (!message->has_snapshot()) continue;
    const physics::wire::Snapshot& s = message->snapshot();
    ASSERT_TRUE(follower.apply(s)) << follower.problem;
    ASSERT_TRUE(peer.send(ack(s.tick())));
    // Its own input changes every 20 ticks; another player joins and leaves.
    if (n % 20 == 0) {
      ASSERT_TRUE(peer.send(input_message(s.tick() + 4, (n % 40) ? 8.0 : -8.0, 3.0)));
    }
    if (n == 60) {
      other = std::make_unique<RawPeer>(server.port());
      ASSERT_TRUE(other->send(hello_message("other")));
    }
    if (n == 150) other.reset();
  }
  EXPECT_GE(follower.followed, 240u);
  EXPECT_GE(follower.compared, 200u);
  EXPECT_EQ(follower.body_records, 0u) << "the relay sends no body records";
  EXPECT_EQ(follower.numbered_on_the_wire, 0u) << "the relayed ticks' numbers are implied";
}

TEST(RelayView, AFullStateRequestIsAnsweredWithTheWorld) {
  RunningServer server(test_config(), scene::default_scene());
  RawPeer peer(server.port());
  ASSERT_TRUE(peer.send(relay_hello("follower")));
  const auto welcome = peer.receive(5s);
  ASSERT_TRUE(welcome && welcome->has_welcome());
  Follower follower;
  ASSERT_TRUE(follower.welcome(welcome->welcome())) << follower.problem;
  bool asked = false;
  for (int n = 0; n < 60 && follower.world_states == 0; ++n) {
    const auto message = peer.receive(5s);
    ASSERT_TRUE(message.has_value());
    if (!message->has_snapshot()) continue;
    ASSERT_TRUE(follower.apply(message->snapshot())) << follower.problem;
    ASSERT_TRUE(peer.send(ack(message->snapshot().tick())));
    if (n == 10 && !asked) {
      physics::wire::ClientMessage request;
      request.mutable_full_state_request();
      ASSERT_TRUE(peer.send(request));
      asked = true;
    }
  }
  EXPECT_EQ(follower.world_states, 1u);
  EXPECT_EQ(server.stats().relay_resyncs, 1u);
}

TEST(RelayView, TheRelayWithoutTheWorldIsRefused) {
  RunningServer server(test_config(), scene::default_scene());
  RawPeer peer(server.port());
  physics::wire::ClientMessage hello = relay_hello("no world");
  hello.mutable_hello()->set_want_world(false);
  ASSERT_TRUE(peer.send(hello));
  const auto error = peer.receive_error(5s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), physics::wire::ERROR_INVALID_VIEW);
  EXPECT_NE(error->message().find("want_world"), std::string::npos) << error->message();
}

}  // namespace
}  // namespace itest
