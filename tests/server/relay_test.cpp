// The input relay (docs/PROTOCOL.md 5.12), socket-free: a world read from the
// server's bytes at some tick and then following the relayed ticks holds the
// server's world bit for bit at every tick, through joins, leaves, reused slots and
// changing inputs; the relay's bytes do not grow with the number of bodies; and a
// relay the world cannot follow is a clear problem, never a crash.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "relay/follow_relay.h"
#include "server/relay_log.h"
#include "server/simulation.h"
#include "test_scene.h"

namespace {

using server::RelayLog;
using server::Simulation;

scene::SceneDef default_scene_file() {
  scene::SceneResult loaded =
      scene::load_scene_file(std::filesystem::path(PHYSICS_SCENES_DIR) / "default.textproto");
  return std::get<scene::SceneDef>(loaded);
}

// A client's world: read from bytes, then fed every tick the relay holds for it.
struct Follower {
  phys::World world;
  std::uint64_t after_tick;
  std::uint64_t first_change;
  std::uint64_t ticks_followed = 0;
  std::uint64_t hashes_checked = 0;

  static Follower at(const Simulation& sim, const RelayLog& log) {
    const std::vector<std::uint8_t> bytes = sim.world().to_bytes();
    std::string error;
    std::optional<phys::World> world = phys::World::from_bytes(bytes, &error);
    EXPECT_TRUE(world.has_value()) << error;
    return Follower{std::move(*world), sim.current_tick(), log.next_change()};
  }

  // Follows the ticks up to the simulation's; true while nothing went wrong.
  bool catch_up(const Simulation& sim, const RelayLog& log, std::uint32_t hash_interval = 1) {
    physics::wire::Snapshot snapshot;
    if (!log.holds_after(after_tick)) return false;
    log.append(after_tick, sim.current_tick(), first_change, hash_interval,
               server::RelayLog::Audience::Followers, snapshot);
    for (const physics::wire::RelayTick& tick : snapshot.relay()) {
      const relay::FollowResult result = relay::follow(world, tick, sim.dt());
      EXPECT_EQ(result.problem, relay::FollowProblem::None) << result.detail;
      if (result.problem != relay::FollowProblem::None) return false;
      ++ticks_followed;
      if (result.hash_checked) ++hashes_checked;
    }
    after_tick = sim.current_tick();
    return true;
  }
};

// Scripted inputs: client c's acceleration at tick t changes every few ticks.
phys::Vec2 scripted(server::ClientId c, std::uint64_t t) {
  const double phase = static_cast<double>((t / (3 + c)) % 5);
  return {(phase - 2.0) * 3.0, (static_cast<double>(c % 3) - 1.0) * 2.5};
}

TEST(InputRelay, AFollowerHoldsTheServersWorldAtEveryTick) {
  Simulation sim(default_scene_file());
  RelayLog log;
  sim.relay_to(&log);
  ASSERT_TRUE(sim.join(1).has_value());
  ASSERT_TRUE(sim.join(2).has_value());
  const auto tick_with_inputs = [&](const std::vector<server::ClientId>& clients) {
    for (const server::ClientId c : clients) {
      sim.submit_input(c, sim.current_tick() + 1, scripted(c, sim.current_tick() + 1));
    }
    sim.step_tick();
  };
  for (int i = 0; i < 20; ++i) tick_with_inputs({1, 2});

  Follower follower = Follower::at(sim, log);  // welcomed at tick 20
  std::vector<server::ClientId> in_room = {1, 2};
  for (int i = 0; i < 200; ++i) {
    // Joins and leaves between ticks: a third player, the first leaving (its slot
    // then reused by a fourth), and a leave and a join in the same gap.
    if (i == 10) {
      ASSERT_TRUE(sim.join(3).has_value());
      in_room = {1, 2, 3};
    }
    if (i == 60) {
      ASSERT_TRUE(sim.leave(1));
      ASSERT_TRUE(sim.join(4).has_value());
      in_room = {2, 3, 4};
    }
    if (i == 120) {
      ASSERT_TRUE(sim.leave(3));
      in_room = {2, 4};
    }
    tick_with_inputs(in_room);
    ASSERT_TRUE(follower.catch_up(sim, log)) << "tick " << sim.current_tick();
    ASSERT_EQ(follower.world.state_hash(), sim.world().state_hash())
        << "tick " << sim.current_tick();
  }
  EXPECT_EQ(follower.ticks_followed, 200u);
  EXPECT_EQ(follower.hashes_checked, 200u);
  EXPECT_EQ(follower.world.body_count(), sim.world().body_count());
}

// A client whose Welcome took the world after some of the changes between two ticks
// is sent only the changes after it; a follower that was sent them all would add a
// body twice.
TEST(InputRelay, AWelcomeBetweenTwoJoinsIsSentOnlyTheSecond) {
  Simulation sim(server_test::free_space_scene());
  RelayLog log;
  sim.relay_to(&log);
  ASSERT_TRUE(sim.join(1).has_value());
  sim.step_tick();
  ASSERT_TRUE(sim.join(2).has_value());
  Follower follower = Follower::at(sim, log);  // holds 1 and 2
  ASSERT_TRUE(sim.join(3).has_value());
  sim.step_tick();
  physics::wire::Snapshot snapshot;
  log.append(follower.after_tick, sim.current_tick(), follower.first_change, 1,
             server::RelayLog::Audience::Followers, snapshot);
  ASSERT_EQ(snapshot.relay_size(), 1);
  ASSERT_EQ(snapshot.relay(0).changes_size(), 1);
  EXPECT_EQ(snapshot.relay(0).changes(0).added().body_id(), sim.body_of(3)->packed());
  ASSERT_TRUE(follower.catch_up(sim, log));
  EXPECT_EQ(follower.world.state_hash(), sim.world().state_hash());

  // Sent every change instead, the follower's world finds the second body there.
  Follower wrong = Follower::at(sim, log);
  physics::wire::Snapshot again;
  log.append(sim.current_tick() - 1, sim.current_tick(), 0, 1,
             server::RelayLog::Audience::Followers, again);
  const relay::FollowResult twice = relay::follow(wrong.world, again.relay(0), sim.dt());
  EXPECT_EQ(twice.problem, relay::FollowProblem::BodyMismatch) << twice.detail;
}

scene::SceneDef crowd(int bodies) {
  scene::SceneDef scene = server_test::free_space_scene();
  for (int i = 0; i < bodies; ++i) {
    phys::BodyDef b;
    b.shape = phys::Shape::Circle;
    b.motion = phys::Motion::Dynamic;
    b.radius = 0.2;
    b.position = {100.0 + (i % 200) * 0.5, 100.0 + (i / 200) * 0.5};
    b.velocity = {(i % 7) * 0.1, (i % 5) * 0.1};
    scene.bodies.push_back(b);
  }
  return scene;
}

// The relay's bytes per tick with 3 players and 1,000 moving bodies, and with 16,000:
// the same, tick for tick (no body records: only what the players did).
TEST(InputRelay, ItsBytesDoNotDependOnTheBodyCount) {
  std::vector<std::vector<std::size_t>> sizes;
  for (const int bodies : {1000, 16000}) {
    Simulation sim(crowd(bodies));
    RelayLog log;
    sim.relay_to(&log);
    std::vector<std::size_t> per_tick;
    for (server::ClientId c = 1; c <= 3; ++c) ASSERT_TRUE(sim.join(c).has_value());
    std::uint64_t sent = 0;
    for (int i = 0; i < 40; ++i) {
      for (server::ClientId c = 1; c <= 3; ++c) {
        sim.submit_input(c, sim.current_tick() + 1, scripted(c, sim.current_tick() + 1));
      }
      sim.step_tick();
      physics::wire::Snapshot snapshot;
      log.append(sent, sim.current_tick(), 0, 4, server::RelayLog::Audience::Followers, snapshot);
      sent = sim.current_tick();
      per_tick.push_back(snapshot.ByteSizeLong());
    }
    sizes.push_back(per_tick);
  }
  EXPECT_EQ(sizes[0], sizes[1]);
  std::size_t total = 0;
  for (const std::size_t s : sizes[1]) total += s;
  EXPECT_LT(total / sizes[1].size(), 120u) << "bytes a tick, 3 players";
}

TEST(InputRelay, AClientTooFarBehindIsNotSentTicksTheLogNoLongerHolds) {
  Simulation sim(server_test::free_space_scene());
  RelayLog log(10);
  sim.relay_to(&log);
  ASSERT_TRUE(sim.join(1).has_value());
  for (int i = 0; i < 30; ++i) sim.step_tick();
  EXPECT_EQ(log.ticks_held(), 10u);
  EXPECT_TRUE(log.holds_after(20));
  EXPECT_FALSE(log.holds_after(19));
  EXPECT_TRUE(log.holds_after(30));
}

// A relay the world cannot follow: each a problem named, the world not crashed.
TEST(InputRelay, ARelayTheWorldCannotFollowIsAProblemNamed) {
  Simulation sim(server_test::free_space_scene());
  ASSERT_TRUE(sim.join(1).has_value());
  Follower follower = Follower::at(sim, RelayLog{});
  const std::uint64_t own = sim.body_of(1)->packed();

  physics::wire::RelayTick tick;
  tick.set_tick(1);
  *tick.add_changes()->mutable_added() = physics::wire::RelayBody{};
  tick.mutable_changes(0)->mutable_added()->set_body_id(own);  // held already
  EXPECT_EQ(relay::follow(follower.world, tick, sim.dt()).problem,
            relay::FollowProblem::BodyMismatch);

  tick.Clear();
  tick.add_changes()->set_removed(own + (1ull << 32));  // a stale generation
  EXPECT_EQ(relay::follow(follower.world, tick, sim.dt()).problem,
            relay::FollowProblem::BodyMismatch);

  tick.Clear();
  physics::wire::RelayInput& input = *tick.add_inputs();
  input.set_body_id(own);
  input.set_ax(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(relay::follow(follower.world, tick, sim.dt()).problem, relay::FollowProblem::BadInput);

  tick.Clear();
  tick.set_state_hash(follower.world.state_hash() ^ 1);  // never matches
  const relay::FollowResult wrong = relay::follow(follower.world, tick, sim.dt());
  EXPECT_EQ(wrong.problem, relay::FollowProblem::HashMismatch);
  EXPECT_TRUE(wrong.hash_checked);

  std::string error;
  EXPECT_FALSE(relay::world_from("not a world", &error).has_value());
  EXPECT_NE(error.find("tag"), std::string::npos) << error;
}

}  // namespace
