#pragma once
// The input relay (ENCODING_INPUTS, docs/PROTOCOL.md "Running the world"): what the
// Simulation did in each tick, as a client that runs the same world needs it. Bodies
// added (with their full definition) and removed since the previous tick, in order;
// the accelerations set before the step that changed a body's acceleration; the
// state hash after it. The Simulation reports to it (Simulation::relay_to); the
// server copies the ticks each relay client has not been sent into its snapshots.
//
// It keeps the last `keep_ticks` ticks: a client further behind is sent the world's
// state again instead. Each change has a sequence number, so that a client whose
// Welcome carried the world as it was in the middle of a tick's changes is sent
// only the changes after it.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "physics/body.h"
#include "physics/game_state.h"
#include "wire.pb.h"

namespace server {

class RelayLog {
 public:
  explicit RelayLog(std::size_t keep_ticks = 600);

  // Reported by the Simulation, in the order they happen.
  void added(phys::BodyId id, const phys::BodyDef& def);
  void removed(phys::BodyId id);
  // Before tick `tick` is stepped: a body's acceleration changed to `acceleration`
  // (the value given to World::set_acceleration).
  void applied(std::uint64_t tick, phys::BodyId body, phys::Vec2 acceleration);
  void stepped(std::uint64_t tick, std::uint64_t state_hash);
  // A body moved by game rules (the values given, each when set).
  void set(phys::BodyId id, std::optional<phys::Vec2> position, std::optional<phys::Vec2> velocity,
           std::optional<phys::Vec2> acceleration);
  // The world's game state, whole (RelayChange.game_state).
  void game_state(const phys::GameState& state);
  // A player joined with this body, or left (RelayTick.joined, left).
  void joined(std::uint32_t client, phys::BodyId body);
  void left(std::uint32_t client);
  // For clients that run the rules: an input the rules were handed at `tick`, and a
  // game message delivered at it (RelayTick.rules_inputs, messages).
  void rules_input(std::uint64_t tick, std::uint32_t client, phys::Vec2 acceleration);
  void game_message(std::uint64_t tick, std::uint32_t client, const std::string& payload);
  // Between these, changes go to the open tick's list of the rules' phase
  // (RelayTick.before_step or after_step) instead of its `changes`.
  enum class RulesPhase { BeforeStep, AfterStep };
  void begin_rules(RulesPhase phase) { phase_ = phase; }
  void end_rules() { phase_.reset(); }

  // The sequence number the next change will get.
  std::uint64_t next_change() const { return next_change_; }
  // Whether the ticks after `after_tick` up to the last stepped are all held.
  bool holds_after(std::uint64_t after_tick) const;
  // What a client is sent of each tick: the rules' changes (before_step, after_step),
  // or, to a client that runs the rules itself, the rules' inputs and messages.
  enum class Audience { Followers, RulesRunners };
  // Appends to `out` the ticks after `after_tick` up to `up_to`, leaving out changes
  // numbered below `first_change`; each tick that is a multiple of `hash_interval`
  // carries its state hash. holds_after(after_tick) must be true.
  void append(std::uint64_t after_tick, std::uint64_t up_to, std::uint64_t first_change,
              std::uint32_t hash_interval, Audience audience, physics::wire::Snapshot& out) const;

  std::size_t ticks_held() const { return ticks_.size(); }

 private:
  struct Tick {
    physics::wire::RelayTick message;  // without its hash
    std::uint64_t state_hash = 0;
    std::uint64_t first_change = 0;  // the sequence number of message.changes(0)
  };
  Tick& open_tick();
  // Where the next change goes: the open tick's changes, or its rules' phase list.
  physics::wire::RelayChange& next_change_slot();

  std::size_t keep_ticks_;
  std::deque<Tick> ticks_;  // stepped, oldest first, consecutive
  Tick open_;               // changes and inputs of the tick not stepped yet
  bool open_started_ = false;
  std::optional<RulesPhase> phase_;
  std::uint64_t next_change_ = 0;
};

class Simulation;

// The players, their bodies and the inputs the rules last saw, ascending client id
// (Welcome.players, Snapshot.players).
void write_players(const Simulation& simulation,
                   google::protobuf::RepeatedPtrField<physics::wire::RelayPlayer>& out);

}  // namespace server
