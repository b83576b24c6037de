#pragma once
// A game's rules on the server's own tick logic (server::Simulation), in the test's
// process and without sockets: players join, set inputs and send game messages, the
// test steps N ticks and reads the authoritative world, finds bodies by name, and
// checks each tick's sensor and contact events and the messages the rules sent. It is
// the Simulation the server runs, so a rule that holds here holds there, tick for
// tick (a networked lockstep run ends at the same hashes).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/world.h"
#include "physics_testing/outcome.h"
#include "scene/scene.h"
#include "server/game_rules.h"
#include "server/simulation.h"

namespace physics_testing {

// Makes a fresh rules object of a game, as the server's config would hold one.
using RulesFactory = std::function<std::shared_ptr<server::GameRules>()>;

// What one tick did.
struct GameTick {
  std::uint64_t tick = 0;
  std::uint64_t state_hash = 0;
  std::vector<phys::SensorEvent> sensor_events;
  std::vector<phys::ContactEvent> contact_events;
  // What the rules sent during the tick (client 0: to everyone).
  std::vector<server::OutgoingGameMessage> messages;
};

class GameRun {
 public:
  // Calls the rules' on_create. Contact events are on (they change no state), so
  // that every tick's are there to check.
  explicit GameRun(scene::SceneDef scene, std::shared_ptr<server::GameRules> rules,
                   server::SimulationOptions options = {});
  // Calls the rules' on_end.
  ~GameRun();
  GameRun(const GameRun&) = delete;
  GameRun& operator=(const GameRun&) = delete;

  // A player joins before the next tick, as a Hello does (the rules' on_join): its
  // client id (1, 2, ... in the order of joining), or why it was not let in (the
  // rules' reason, or no free spawn point).
  Expected<server::ClientId> join(std::optional<std::uint32_t> seat = std::nullopt);
  // The player leaves before the next tick (the rules' on_leave).
  Outcome leave(server::ClientId client);
  // The player's input for the next tick: its acceleration from then on, clamped to
  // the scene's max_acceleration as the server clamps it.
  Outcome input(server::ClientId client, double ax, double ay);
  // A game message from the player for the rules at the next tick, with the
  // server's limits (size, count a tick).
  Outcome message(server::ClientId client, std::string payload);

  // Test-only edits of the world between ticks, as the rules' GameWorld makes them
  // (reaching snapshots and the input relay as changes before the next tick). No
  // recording holds them: a replay runs only the rules, so a run that uses them is
  // not one to record and replay.
  Expected<phys::BodyId> add_body(const phys::BodyDef& def);
  Outcome remove_body(phys::BodyId id);
  Outcome set_position(phys::BodyId id, double x, double y);
  Outcome set_velocity(phys::BodyId id, double vx, double vy);
  // The game's variables and timers (the world's, GameWorld::set_int and the rest).
  const phys::GameState& game_state() const { return simulation_.world().game_state(); }

  // Steps `ticks` ticks (at least one); returns the last one's record.
  const GameTick& step(std::uint64_t ticks = 1);
  // Every tick stepped, in order.
  const std::vector<GameTick>& history() const { return history_; }
  std::uint64_t tick() const { return simulation_.current_tick(); }

  const phys::World& world() const { return simulation_.world(); }
  std::optional<phys::BodyId> find_body(std::string_view name) const;
  // A body by its name: its state now, or nullopt when no body has that name.
  std::optional<phys::BodyState> body(std::string_view name) const;
  std::optional<phys::BodyId> body_of(server::ClientId client) const;
  // The payloads the rules sent to the player (its own and everyone's), oldest first.
  std::vector<std::string> messages_to(server::ClientId client) const;

  server::Simulation& simulation() { return simulation_; }

 private:
  server::Simulation simulation_;
  server::ClientId next_client_ = 1;
  std::vector<GameTick> history_;
};

}  // namespace physics_testing
