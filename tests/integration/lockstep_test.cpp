// Lockstep equals in-process: clients in lockstep send a scripted sequence of
// inputs; the state hashes they receive equal, tick by tick, those of the same
// scene stepped in-process with the same inputs, by a plain phys::World and by the
// server's own tick logic (server::Simulation).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "harness.h"
#include "reference.h"
#include "server/simulation.h"
#include "test_scenes.h"

namespace itest {
namespace {

// Client k's scripted acceleration at tick t: different for every client and tick,
// within the scene's maximum so that no clamping is involved.
client::Vec2 scripted_input(std::size_t k, std::uint64_t t) {
  const double phase = static_cast<double>(t) * 0.21 + static_cast<double>(k) * 1.7;
  const double magnitude = 4.0 + 3.0 * static_cast<double>(k);
  return {magnitude * std::cos(phase), magnitude * std::sin(phase) + 6.0};
}

void run_lockstep_against_reference(const scene::SceneDef& scene, std::size_t clients, int ticks) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;  // no tick may be stepped without every input
  RunningServer server(config, scene);

  std::vector<std::unique_ptr<client::Client>> players;
  for (std::size_t k = 0; k < clients; ++k) {
    players.push_back(std::make_unique<client::Client>(
        server.exact_client_config("lockstep-" + std::to_string(k))));
    ASSERT_TRUE(players.back()->connect(3s)) << players.back()->last_error().to_string();
  }
  // Nobody has sent an input yet, so no tick was stepped and every client joined at
  // tick 0, each at the next spawn point.
  const std::uint64_t start_tick = players.front()->welcome().current_tick;
  ASSERT_EQ(start_tick, 0u);
  ReferenceRun reference(scene);
  // Simulation is the server's own tick logic, so a bug in it would be in both: the
  // plain world of ReferenceRun is the independent oracle, Simulation the check
  // that the server steps what its own class steps.
  server::Simulation simulation(scene);
  for (std::size_t k = 0; k < players.size(); ++k) {
    const client::Welcome& welcome = players[k]->welcome();
    ASSERT_EQ(welcome.current_tick, start_tick);
    ASSERT_EQ(reference.add_player(welcome), welcome.body_id);
    const auto body = simulation.join(welcome.client_id);
    ASSERT_TRUE(body.has_value());
    ASSERT_EQ(body->packed(), welcome.body_id);
    for (const client::BodyShape& shape : welcome.bodies) {
      if (shape.body_id != welcome.body_id) continue;
      ASSERT_LT(k, scene.spawn_points.size());
      EXPECT_EQ(shape.position.x, scene.spawn_points[k].x) << "client " << k;
      EXPECT_EQ(shape.position.y, scene.spawn_points[k].y) << "client " << k;
    }
  }

  for (int i = 1; i <= ticks; ++i) {
    const std::uint64_t tick = start_tick + static_cast<std::uint64_t>(i);
    for (std::size_t k = 0; k < players.size(); ++k) {
      const client::Vec2 a = scripted_input(k, tick);
      ASSERT_TRUE(players[k]->send_input(tick, a.x, a.y));
      reference.set_input(players[k]->welcome().body_id, a.x, a.y);
      simulation.submit_input(players[k]->welcome().client_id, tick, {a.x, a.y});
    }
    const std::uint64_t expected_hash = reference.step();
    simulation.step_tick();
    ASSERT_EQ(simulation.world().state_hash(), expected_hash) << "tick " << tick;
    for (std::size_t k = 0; k < players.size(); ++k) {
      auto snapshot = players[k]->next_snapshot(5s);
      ASSERT_TRUE(snapshot.has_value())
          << "client " << k << " tick " << tick << ": " << players[k]->last_error().to_string();
      ASSERT_EQ(snapshot->tick, tick) << "client " << k;
      ASSERT_EQ(snapshot->state_hash, expected_hash) << "client " << k << " tick " << tick;
      EXPECT_EQ(snapshot->last_applied_input_tick, tick);
    }
  }
  // Stats are published just after the snapshots are queued.
  const auto last_tick = start_tick + static_cast<std::uint64_t>(ticks);
  EXPECT_TRUE(eventually([&] { return server.stats().current_tick == last_tick; }));
  const server::ServerStats stats = server.stats();
  EXPECT_EQ(stats.lockstep_timeouts, 0u);
  EXPECT_EQ(stats.reused_inputs, 0u);
  EXPECT_EQ(stats.late_inputs, 0u);
}

TEST(Lockstep, ThreeClientsOnTheDefaultSceneMatchInProcessHashes) {
  run_lockstep_against_reference(scene::default_scene(), 3, 120);
}

TEST(Lockstep, TwoClientsInFreeFlightMatchInProcessHashes) {
  run_lockstep_against_reference(free_flight_scene(true), 2, 60);
}

// Predicted clients over the network: at every tick each holds exactly what the
// server believes it holds (the view hash of every snapshot equals its own), and
// every body it holds is within its tolerances of the same scene stepped in-process.
TEST(Lockstep, PredictedClientsHoldTheWorldWithinTheirToleranceAtEveryTick) {
  const scene::SceneDef scene = scene::default_scene();
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;
  RunningServer server(config, scene);
  std::vector<std::unique_ptr<client::Client>> players;
  for (std::size_t k = 0; k < 2; ++k) {
    players.push_back(
        std::make_unique<client::Client>(server.client_config("predicted-" + std::to_string(k))));
    ASSERT_TRUE(players.back()->connect(3s)) << players.back()->last_error().to_string();
  }
  const std::uint64_t start_tick = players.front()->welcome().current_tick;
  ReferenceRun reference(scene);
  reference.advance_to(start_tick);
  for (const auto& player : players) {
    ASSERT_EQ(reference.add_player(player->welcome()), player->welcome().body_id);
  }
  const client::View& view = players.front()->welcome().view;
  ASSERT_EQ(view.encoding, client::Encoding::Predicted);
  std::uint64_t records = 0;
  for (int i = 1; i <= 300; ++i) {
    const std::uint64_t tick = start_tick + static_cast<std::uint64_t>(i);
    for (std::size_t k = 0; k < players.size(); ++k) {
      const client::Vec2 a = scripted_input(k, tick);
      ASSERT_TRUE(players[k]->send_input(tick, a.x, a.y));
      reference.set_input(players[k]->welcome().body_id, a.x, a.y);
    }
    reference.step();
    for (std::size_t k = 0; k < players.size(); ++k) {
      auto snapshot = players[k]->next_snapshot(5s);
      ASSERT_TRUE(snapshot.has_value()) << players[k]->last_error().to_string();
      ASSERT_EQ(snapshot->tick, tick);
      ASSERT_TRUE(snapshot->in_sync) << "client " << k << " tick " << tick;
      records += snapshot->records;
      for (const client::BodyState& body : snapshot->bodies) {
        const auto truth = reference.body(body.body_id);
        ASSERT_TRUE(truth.has_value());
        ASSERT_LE(std::abs(body.position.x - truth->position.x), view.position_tolerance);
        ASSERT_LE(std::abs(body.position.y - truth->position.y), view.position_tolerance);
        ASSERT_LE(std::abs(body.velocity.x - truth->velocity.x), view.velocity_tolerance);
        ASSERT_LE(std::abs(body.velocity.y - truth->velocity.y), view.velocity_tolerance);
      }
      ASSERT_EQ(snapshot->bodies.size(), reference.world().dynamic_body_count());
    }
  }
  EXPECT_EQ(players[0]->stats().desyncs + players[1]->stats().desyncs, 0u);
  // Both share one view: one encoding a tick for the two of them.
  EXPECT_EQ(server.stats().views, 1u);
  EXPECT_GT(records, 0u);
}

// The server's result does not depend on the order in which inputs arrive: in one
// run client a's input for each tick is sent first, in the other client b's, and in
// both the order flips every third tick. Each run equals, tick by tick, the same
// script stepped in-process, so the two runs also equal each other.
TEST(Lockstep, NetworkRunDoesNotDependOnTheOrderInputsArrive) {
  std::vector<std::uint64_t> runs[2];
  for (int run = 0; run < 2; ++run) {
    server::ServerConfig config = test_config(true);
    config.lockstep_timeout = 10s;
    const scene::SceneDef scene = scene::default_scene();
    RunningServer server(config, scene);
    client::Client a(server.exact_client_config("a"));
    client::Client b(server.exact_client_config("b"));
    ASSERT_TRUE(a.connect(3s));
    ASSERT_TRUE(b.connect(3s));
    const std::uint64_t start = a.welcome().current_tick;
    ReferenceRun reference(scene);
    reference.advance_to(start);
    ASSERT_EQ(reference.add_player(a.welcome()), a.welcome().body_id);
    ASSERT_EQ(reference.add_player(b.welcome()), b.welcome().body_id);
    for (std::uint64_t t = start + 1; t <= start + 40; ++t) {
      const client::Vec2 ia = scripted_input(0, t);
      const client::Vec2 ib = scripted_input(1, t);
      const bool a_first = (run == 0) != (t % 3 == 0);
      client::Client& first = a_first ? a : b;
      client::Client& second = a_first ? b : a;
      const client::Vec2 i1 = a_first ? ia : ib;
      const client::Vec2 i2 = a_first ? ib : ia;
      ASSERT_TRUE(first.send_input(t, i1.x, i1.y));
      ASSERT_TRUE(second.send_input(t, i2.x, i2.y));
      reference.set_input(a.welcome().body_id, ia.x, ia.y);
      reference.set_input(b.welcome().body_id, ib.x, ib.y);
      const std::uint64_t expected = reference.step();
      auto sa = a.next_snapshot(5s);
      auto sb = b.next_snapshot(5s);
      ASSERT_TRUE(sa && sb);
      ASSERT_EQ(sa->state_hash, expected) << "run " << run << " tick " << t;
      ASSERT_EQ(sb->state_hash, expected) << "run " << run << " tick " << t;
      runs[run].push_back(sa->state_hash);
    }
  }
  EXPECT_EQ(runs[0], runs[1]);
}

}  // namespace
}  // namespace itest
