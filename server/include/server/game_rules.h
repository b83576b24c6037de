#pragma once
// A game on the server: rules the Simulation calls at fixed points of every tick,
// through a narrow handle on the world (docs/SERVER.md, "Your game on the server").
//
// Deterministic by construction: a rule sees the tick, the world, the players and
// their inputs, nothing else (no clock, no network, no order of connections beyond
// the ticks they joined in). A recorded run is replayed by running the same rules
// again (replay::Replayer with the rules): the recording holds joins, leaves and
// inputs, and each tick's hash checks that the rules did the same.
//
// The order within a tick (Simulation::step_tick):
//   joins and leaves since the previous tick (on_join, on_joined, on_leave, as they
//   happen)
//   the inputs due at the tick applied to the players' bodies
//   on_timer for each timer due at the tick, in (due tick, name, index) order
//   before_step(world, inputs)
//   the world's step
//   after_step(world, contact events of the step)
// on_create once, when the Simulation is made (the scene loaded, tick 0); on_end
// when the server stops. A rule that throws fails the tick, as any tick failure.
//
// What the rules keep from one tick to the next belongs in the world's game state
// (GameWorld::set_int, set_number, start_timer), not in the rules' own members: a
// saved and restored world, a replay, a resync and a late joiner's world carry the
// game state, and the state hash covers it. physics_testing::check_rules_state_in_world
// catches a rule that keeps state in its members.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/world.h"
#include "server/room.h"

namespace server {

// An input applied at this tick that changed the player's acceleration (a player's
// first, or one that differs from its last: the inputs a recording holds, so that a
// replay hands the rules the same list): the player, its body, the acceleration.
struct AppliedInput {
  ClientId client = 0;
  phys::BodyId body;
  phys::Vec2 acceleration{};
};

// A client's game message, delivered at its tick (GameWorld::messages).
struct ClientGameMessage {
  ClientId client = 0;
  std::string payload;
};

// What on_join decides. Default: the scene's player body at a free spawn point.
struct JoinDecision {
  // Set: the player is refused, and its Error says this (ERROR_REFUSED_BY_GAME).
  std::optional<std::string> refuse;
  // Set: the player's body, instead of the scene's player at a spawn point. Its
  // motion must be dynamic (the player sets its acceleration).
  std::optional<phys::BodyDef> body;
};

// A message the rules sent (GameWorld::send, broadcast): client 0 is everyone.
struct OutgoingGameMessage {
  ClientId client = 0;
  std::uint64_t tick = 0;
  std::string payload;
};

inline constexpr std::size_t kMaxOutgoingGameMessageBytes = 65536;

// What runs the rules and what a GameWorld works on: the server's Simulation, and a
// predicting client's world (client/prediction_core.h), which runs the same rules on
// the same ticks. The reports let the server pass the rules' changes on to snapshots
// and the relay; a predicting client keeps only the messages.
class RulesHost {
 public:
  virtual phys::World& rules_world() = 0;
  virtual const phys::World& rules_world() const = 0;
  // The players in the world, ascending id, with their bodies.
  virtual const std::map<ClientId, phys::BodyId>& rules_players() const = 0;
  // The tick being stepped (or the last one stepped, between ticks).
  virtual std::uint64_t rules_tick() const = 0;
  virtual double rules_dt() const = 0;
  // The game messages delivered at this tick (empty outside before_step).
  virtual const std::vector<ClientGameMessage>& rules_messages() const = 0;
  // A body the rules made, one they removed, and one they moved (each value given).
  virtual void rules_added(phys::BodyId id, const phys::BodyDef& def) = 0;
  virtual void rules_removed(phys::BodyId id) = 0;
  virtual void rules_set(phys::BodyId id, std::optional<phys::Vec2> position,
                         std::optional<phys::Vec2> velocity,
                         std::optional<phys::Vec2> acceleration) = 0;
  // GameWorld::send and broadcast (client 0), already checked against the limit.
  virtual void rules_send(OutgoingGameMessage message) = 0;

 protected:
  ~RulesHost() = default;
};

// The rules' handle on the world: read anything, change bodies, nothing else. What
// the rules change reaches every client as any change does (bodies added and
// removed in snapshots; every change in the input relay, docs/PROTOCOL.md 5.12).
class GameWorld {
 public:
  // The handle the host gives the rules for one call.
  explicit GameWorld(RulesHost& host) : host_(host) {}

  // The tick being stepped (before_step, after_step), or the last one stepped.
  std::uint64_t tick() const;
  double dt() const;

  // Bodies made and removed by the rules. The world's limits answer (max_bodies:
  // BodyDefError::TooManyBodies, coordinates beyond 1e7: OutOfBounds). A player's
  // own body cannot be destroyed here (false): the player leaves instead.
  phys::BodyId create(const phys::BodyDef& def, phys::BodyDefError* error = nullptr);
  bool destroy(phys::BodyId id);
  // Each false for an unknown id or a value the world refuses (World's setters).
  bool set_position(phys::BodyId id, phys::Vec2 position);
  bool set_velocity(phys::BodyId id, phys::Vec2 velocity);
  bool set_acceleration(phys::BodyId id, phys::Vec2 acceleration);
  // Velocity += impulse / mass, on a dynamic body.
  bool apply_impulse(phys::BodyId id, phys::Vec2 impulse);

  std::optional<phys::BodyState> body(phys::BodyId id) const;
  std::vector<phys::BodyState> bodies() const;
  std::size_t body_count() const;
  // The player's body, if the player is in the world.
  std::optional<phys::BodyId> body_of(ClientId client) const;
  // The players in the world, ascending id, with their bodies.
  const std::map<ClientId, phys::BodyId>& players() const;
  // The last step's contact events (after_step; GameRules::wants_contact_events).
  const std::vector<phys::ContactEvent>& contact_events() const;
  // The last step's sensor events (after_step): bodies entering and leaving sensors.
  const std::vector<phys::SensorEvent>& sensor_events() const;
  // The last step's crushes (after_step): a dynamic body pinned between a moving
  // kinematic body and a static one (physics/crush_events.h), to kill or respawn.
  const std::vector<phys::CrushEvent>& crush_events() const;
  // A body by its name (the lowest id of that name), and a body's name.
  std::optional<phys::BodyId> find_body(std::string_view name) const;
  std::uint64_t state_hash() const;

  // The world's queries, as World's (physics/query.h: what each finds, exactly, and
  // what it costs): a ray's first hit or all its hits, the bodies in a box, a circle
  // or at a point, a moving circle's or box's first hit. Answers are values: bodies
  // may be created or destroyed while going through them.
  std::optional<phys::CastHit> cast_ray(phys::Vec2 origin, phys::Vec2 translation,
                                        const phys::QueryFilter& filter = {},
                                        phys::QueryError* error = nullptr) const;
  std::vector<phys::CastHit> cast_ray_all(phys::Vec2 origin, phys::Vec2 translation,
                                          const phys::QueryFilter& filter = {},
                                          phys::QueryError* error = nullptr) const;
  std::vector<phys::BodyId> overlap_box(const phys::Aabb& box, const phys::QueryFilter& filter = {},
                                        phys::QueryError* error = nullptr) const;
  std::vector<phys::BodyId> overlap_circle(phys::Vec2 center, double radius,
                                           const phys::QueryFilter& filter = {},
                                           phys::QueryError* error = nullptr) const;
  std::vector<phys::BodyId> overlap_point(phys::Vec2 point, const phys::QueryFilter& filter = {},
                                          phys::QueryError* error = nullptr) const;
  std::optional<phys::CastHit> cast_circle(phys::Vec2 center, double radius, phys::Vec2 translation,
                                           const phys::QueryFilter& filter = {},
                                           phys::QueryError* error = nullptr) const;
  std::optional<phys::CastHit> cast_box(phys::Vec2 center, phys::Vec2 half_extents,
                                        phys::Vec2 translation,
                                        const phys::QueryFilter& filter = {},
                                        phys::QueryError* error = nullptr) const;

  // The game's variables and timers, in the world (phys::GameState): keyed by a
  // name (1 to 64 bytes) and an index (e.g. a client or a body id), at most 4096
  // entries in all. A value the state refuses (an empty or long name, a new entry
  // beyond the limit, a number not finite) changes nothing: false, and *error says
  // why.
  std::int64_t get_int(std::string_view name, std::uint64_t index = 0,
                       std::int64_t fallback = 0) const;
  double get_number(std::string_view name, std::uint64_t index = 0, double fallback = 0.0) const;
  bool set_int(std::string_view name, std::int64_t value, std::uint64_t index = 0,
               phys::GameStateError* error = nullptr);
  bool set_number(std::string_view name, double value, std::uint64_t index = 0,
                  phys::GameStateError* error = nullptr);
  // Removes the integer and the number of that key: true when there was either.
  bool erase(std::string_view name, std::uint64_t index = 0);
  // A timer: GameRules::on_timer(name, index) at tick tick() + after_ticks (after the
  // inputs of that tick, before before_step), then every `every_ticks` ticks after
  // it (0: once). after_ticks is at least 1. Starting a running timer starts it
  // again.
  bool start_timer(std::string_view name, std::uint64_t after_ticks, std::uint64_t every_ticks = 0,
                   std::uint64_t index = 0, phys::GameStateError* error = nullptr);
  // True when the timer was running.
  bool cancel_timer(std::string_view name, std::uint64_t index = 0);
  const phys::GameState& game_state() const;

  // The players' game messages for this tick (before_step; empty elsewhere), in
  // ascending client, each client's in the order they arrived.
  const std::vector<ClientGameMessage>& messages() const;
  // Messages to a player, or to every player and spectator, sent once the tick's
  // snapshots are (ServerMessage.game_message, stamped with the tick). False for a
  // payload over 65,536 bytes (nothing sent). In a predicting client that runs the
  // rules they are its predicted messages (PredictionCore::predicted_messages).
  bool send(ClientId client, std::string payload);
  bool broadcast(std::string payload);

 private:
  RulesHost& host_;
};

class GameRules {
 public:
  virtual ~GameRules() = default;
  virtual void on_create(GameWorld& /*world*/) {}
  // A player joins (its seat, in a lockstep lobby, or nullopt).
  virtual JoinDecision on_join(GameWorld& /*world*/, ClientId /*client*/,
                               std::optional<std::uint32_t> /*seat*/) {
    return {};
  }
  // A player is in the world, with this body (the rules' own or the scene's player):
  // right after on_join let it in and the body was made.
  virtual void on_joined(GameWorld& /*world*/, ClientId /*client*/, phys::BodyId /*body*/) {}
  // A player left; its body is gone already.
  virtual void on_leave(GameWorld& /*world*/, ClientId /*client*/) {}
  virtual void before_step(GameWorld& /*world*/, const std::vector<AppliedInput>& /*inputs*/) {}
  virtual void after_step(GameWorld& /*world*/) {}
  // A timer started with GameWorld::start_timer is due (at its tick, before
  // before_step). A periodic one is already scheduled again when this is called.
  virtual void on_timer(GameWorld& /*world*/, std::string_view /*name*/, std::uint64_t /*index*/) {}
  virtual void on_end(GameWorld& /*world*/) {}
  // True: the world produces contact events every step, for after_step.
  virtual bool wants_contact_events() const { return false; }
};

}  // namespace server
