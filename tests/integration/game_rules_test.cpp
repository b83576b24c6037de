// Game rules on a real server (server/game_rules.h): in lockstep over TCP, with rules
// that make, push, move and remove bodies, every tick's state hash equals an
// in-process Simulation's with the same rules, joins and inputs; a player the rules
// refuse gets ERROR_REFUSED_BY_GAME with the game's reason.
#include "server/game_rules.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "harness.h"
#include "physics_testing/clients.h"
#include "server/simulation.h"

namespace itest {
namespace {

// A small game: a crate appears every 10 ticks above the players (and every client
// is told), every player gets a kick upward each 15 ticks, a player who sends
// "jump" is kicked up at that tick, and the oldest crate is moved back up after 50.
class CrateRules : public server::GameRules {
 public:
  std::vector<phys::BodyId> crates;
  void before_step(server::GameWorld& w, const std::vector<server::AppliedInput>& inputs) override {
    if (w.tick() % 10 == 0) {
      phys::BodyDef crate;
      crate.shape = phys::Shape::Box;
      crate.half_extents = {0.4, 0.4};
      crate.position = {-3.0 + static_cast<double>(crates.size() % 7), 8.0};
      crates.push_back(w.create(crate));
      w.broadcast("crate " + std::to_string(crates.size()));
    }
    for (const server::ClientGameMessage& m : w.messages()) {
      if (m.payload == "jump") w.apply_impulse(*w.body_of(m.client), {0.0, 5.0});
    }
    if (w.tick() % 15 == 0) {
      for (const server::AppliedInput& input : inputs) w.apply_impulse(input.body, {0.0, 3.0});
    }
  }
  void after_step(server::GameWorld& w) override {
    if (w.tick() % 50 == 0 && !crates.empty()) w.set_position(crates.front(), {0.0, 12.0});
    if (crates.size() > 6) {
      w.destroy(crates.front());
      crates.erase(crates.begin());
    }
  }
};

client::Vec2 scripted(std::size_t k, std::uint64_t tick) {
  const double phase = static_cast<double>(tick) * 0.11 + static_cast<double>(k);
  return {6.0 * std::cos(phase), 2.0 * std::sin(phase)};
}

TEST(GameRulesOverTcp, LockstepWithRulesEqualsTheInProcessRun) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;  // no tick without every input
  config.rules = std::make_shared<CrateRules>();
  RunningServer server(config, scene::default_scene());
  auto clients = physics_testing::connect_clients(server.exact_client_config("player"), 2);
  ASSERT_TRUE(clients) << clients.message();

  // In-process: the same scene and rules, the players joined in the order the server
  // joined them (their Hellos', which their body ids tell), under their client ids.
  server::Simulation reference(scene::default_scene(), {}, std::make_shared<CrateRules>());
  std::vector<std::pair<std::uint64_t, std::size_t>> joined;  // body id, index
  for (std::size_t k = 0; k < clients->size(); ++k) {
    joined.push_back({(*clients)[k]->welcome().body_id, k});
  }
  std::sort(joined.begin(), joined.end());
  for (const auto& [body_id, k] : joined) {
    const auto body = reference.join((*clients)[k]->welcome().client_id);
    ASSERT_TRUE(body.has_value());
    EXPECT_EQ(body->packed(), body_id);
  }
  const std::uint64_t start = (*clients)[0]->welcome().current_tick;
  ASSERT_EQ(start, reference.current_tick());
  for (std::uint64_t tick = start + 1; tick <= start + 150; ++tick) {
    for (std::size_t k = 0; k < clients->size(); ++k) {
      const client::Vec2 a = scripted(k, tick);
      if (k == 0 && tick % 20 == 5) {
        // Before the input of its tick, so that the tick the input completes has it.
        ASSERT_TRUE((*clients)[k]->send_game_message(tick, "jump"));
        reference.submit_game_message((*clients)[k]->welcome().client_id, tick, "jump");
      }
      ASSERT_TRUE((*clients)[k]->send_input(tick, a.x, a.y));
      reference.submit_input((*clients)[k]->welcome().client_id, tick, {a.x, a.y});
    }
    reference.step_tick();
    for (std::size_t k = 0; k < clients->size(); ++k) {
      auto snapshot = physics_testing::wait_for_snapshot(
          *(*clients)[k], [&](const client::Snapshot& s) { return s.tick >= tick; }, 5s);
      ASSERT_TRUE(snapshot) << snapshot.message();
      ASSERT_EQ(snapshot->tick, tick);
      ASSERT_EQ(snapshot->state_hash, reference.world().state_hash())
          << "tick " << tick << ", client " << k;
    }
  }
  std::uint64_t jumps = 0;
  for (std::uint64_t tick = start + 1; tick <= start + 150; ++tick) jumps += tick % 20 == 5;
  EXPECT_EQ(server.stats().game_messages, jumps);
  // The rules' messages reached the players, stamped with their ticks.
  const std::vector<client::GameMessage> told = (*clients)[1]->take_game_messages();
  ASSERT_FALSE(told.empty());
  EXPECT_EQ(told.front().payload, "crate 1");
  EXPECT_EQ(told.front().tick % 10, 0u);
}

class NoLateComers : public server::GameRules {
 public:
  server::JoinDecision on_join(server::GameWorld& w, server::ClientId,
                               std::optional<std::uint32_t>) override {
    server::JoinDecision decision;
    if (w.players().size() >= 1) decision.refuse = "the match is full";
    return decision;
  }
};

TEST(GameRulesOverTcp, APlayerTheGameRefusesIsToldWhy) {
  server::ServerConfig config = test_config();
  config.rules = std::make_shared<NoLateComers>();
  RunningServer server(config, scene::default_scene());
  RawPeer first(server.port());
  ASSERT_TRUE(first.send(hello_message("first")));
  const auto welcome = first.receive(5s);
  ASSERT_TRUE(welcome && welcome->has_welcome());
  RawPeer second(server.port());
  ASSERT_TRUE(second.send(hello_message("second")));
  const auto error = second.receive_error(5s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), physics::wire::ERROR_REFUSED_BY_GAME);
  EXPECT_EQ(error->message(), "refused by the game: the match is full");
  EXPECT_TRUE(second.wait_closed(5s));
  EXPECT_TRUE(
      eventually([&] { return dropped(server.stats(), server::DropReason::RefusedByGame) == 1; }));
}

}  // namespace
}  // namespace itest
