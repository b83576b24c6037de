#pragma once
// The server's tick logic without sockets: the world, the room (who owns which
// body), every client's inputs, and one tick at a time. The network layer feeds it;
// tests (and the lockstep integration test, to replay a run in-process) drive it
// directly. Everything here is deterministic: the state after tick N depends only
// on the scene, the order clients joined and left between ticks, and the inputs.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "physics/world.h"
#include "scene/scene.h"
#include "server/game_rules.h"
#include "server/input_buffer.h"
#include "server/room.h"
#include "server/tick_recorder.h"

namespace server {

class RelayLog;

struct SimulationOptions {
  // Ticks per second; 0 takes the scene's. dt = 1 / tick_rate.
  double tick_rate = 0.0;
  std::uint64_t max_ticks_ahead = 120;
};

// Bodies that appeared or vanished since the last take_changes(), for snapshots.
struct BodyChanges {
  std::vector<phys::BodyId> added;
  std::vector<std::uint64_t> removed;  // packed ids
  bool empty() const { return added.empty() && removed.empty(); }
};

// What Simulation::admit decided for a player.
struct Admission {
  std::optional<phys::BodyId> body;    // set: the player is in the world
  std::optional<std::string> refused;  // the rules refused it, for this reason
};

// Limits on the players' game messages (docs/PROTOCOL.md 3.9).
inline constexpr std::size_t kMaxGameMessageBytes = 256;
inline constexpr std::size_t kMaxGameMessagesPerTick = 4;  // a client's, at one tick

enum class GameMessageVerdict : std::uint8_t {
  OnTime,       // filed at the tick it names
  Late,         // its tick was already stepped: filed at the next tick
  TooFarAhead,  // beyond current + max_ticks_ahead: dropped
  NotJoined,    // the client is not in the world: dropped
  NoGame,       // the simulation has no game rules: dropped
  TooLarge,     // over kMaxGameMessageBytes: dropped
  TooMany,      // the client has kMaxGameMessagesPerTick at that tick already: dropped
};

struct TickResult {
  std::uint64_t tick = 0;  // the tick just stepped
  // Joined clients with no input due at this tick, who kept their held input
  // (in lockstep mode after a timeout, these are the reused inputs).
  std::vector<ClientId> held_over;
};

// The server's host of the rules (RulesHost, privately: only GameWorld calls it).
class Simulation final : private RulesHost {
 public:
  // `rules`, when given, are called at their points of every tick (game_rules.h);
  // on_create is called here.
  explicit Simulation(scene::SceneDef scene, SimulationOptions options = {},
                      std::shared_ptr<GameRules> rules = nullptr);

  // Gives the client a body at a free spawn position (see spawn.h). nullopt when
  // the client already has one or no position is free. `seat` puts the seat's own
  // spawn point first (find_spawn_position).
  std::optional<phys::BodyId> join(ClientId client,
                                   std::optional<std::uint32_t> seat = std::nullopt);
  // join, saying why not when the rules refused the player (GameRules::on_join);
  // without a body and a reason: no free spawn position.
  Admission admit(ClientId client, std::optional<std::uint32_t> seat = std::nullopt);
  bool leave(ClientId client);
  // The server stops: the rules' on_end. Once.
  void end();
  bool has_rules() const { return rules_ != nullptr; }

  // Checks and files one input of `client` (see check_input). Inputs of clients
  // not in the room are refused (NotJoined) and never filed.
  InputCheck submit_input(ClientId client, std::uint64_t tick, phys::Vec2 acceleration);
  // Files an input a recording says was applied at `tick` (> current_tick()), as it
  // was, without check_input: it was checked and clamped when it was recorded, and
  // clamping twice could move it by a rounding. False for a client not in the room.
  bool file_recorded_input(ClientId client, std::uint64_t tick, phys::Vec2 acceleration);
  // A game message of `client` for the rules at `tick` (checked as inputs are, and
  // against the limits above). Accepted ones are delivered at their tick, recorded.
  GameMessageVerdict submit_game_message(ClientId client, std::uint64_t tick, std::string payload);
  // One a recording says was delivered at `tick`, as it was. False for a client not
  // in the room.
  bool file_recorded_game_message(ClientId client, std::uint64_t tick, std::string payload);
  // The rules' messages since the last call, in the order sent.
  std::vector<OutgoingGameMessage> take_outgoing_messages() { return std::exchange(outgoing_, {}); }

  // From now on, joins, leaves, applied inputs and tick hashes go to `recorder`
  // (nullptr stops recording and closes the file). Recording changes no result. A
  // replay starts from the scene's world at tick 0, so attach it before the first
  // join and the first tick (the server does so in its constructor).
  void record_to(std::unique_ptr<TickRecorder> recorder) { recorder_ = std::move(recorder); }
  TickRecorder* recorder() const { return recorder_.get(); }

  // From now on, bodies added and removed, accelerations changed and each tick's
  // state hash go to `relay` too (relay_log.h), which must outlive this or be
  // detached with nullptr. Changes no result; costs a state hash per tick.
  // The game state goes to the relay whole, after a join, a leave or a tick that
  // changed it (RelayChange.game_state), compared with the last one sent.
  void relay_to(RelayLog* relay) {
    relay_ = relay;
    relayed_game_state_ = world_.game_state();  // what a follower is welcomed with
  }

  // For the lockstep gate: about the next tick (current_tick() + 1).
  bool all_inputs_present() const;
  bool any_input_present() const;

  // Applies every client's input due at the next tick to that client's own body
  // (clients in ascending id order), then steps the world by dt.
  TickResult step_tick();

  std::uint64_t current_tick() const { return current_tick_; }
  double dt() const { return dt_; }
  double tick_rate() const { return tick_rate_; }
  std::uint64_t max_ticks_ahead() const { return options_.max_ticks_ahead; }
  const scene::SceneDef& scene() const { return scene_; }
  const phys::World& world() const { return world_; }
  // Contact events from the world's steps (World::set_contact_events): they change
  // no state, so a run records and replays the same with them on or off.
  // Rules that want them keep them on (GameRules::wants_contact_events).
  void set_contact_events(bool on) {
    world_.set_contact_events(on || (rules_ && rules_->wants_contact_events()));
  }
  const Room& room() const { return room_; }
  std::optional<phys::BodyId> body_of(ClientId client) const { return room_.body_of(client); }
  // The client's input state (nullptr for a client not in the room).
  const ClientInputs* inputs_of(ClientId client) const;
  // The client's input the rules last saw (AppliedInput), if any.
  std::optional<phys::Vec2> last_rules_input(ClientId client) const {
    const auto it = last_applied_.find(client);
    if (it == last_applied_.end()) return std::nullopt;
    return it->second;
  }

  BodyChanges take_changes();

  // A handle on the world between ticks, for tests and tools (physics_testing::GameRun):
  // its changes reach snapshots and the relay as the rules' do, as changes before
  // the next tick, but no recording holds them (a replay runs only the rules).
  GameWorld world_handle();
  // From now on `rules` are called in place of the ones given, without on_create:
  // what the old rules made is in the world already. For the check that rules keep
  // nothing outside the world (physics_testing::check_rules_state_in_world).
  void replace_rules(std::shared_ptr<GameRules> rules);

 private:
  // RulesHost: the rules' GameWorld works on this world, room and tick.
  phys::World& rules_world() override { return world_; }
  const phys::World& rules_world() const override { return world_; }
  const std::map<ClientId, phys::BodyId>& rules_players() const override { return room_.members(); }
  std::uint64_t rules_tick() const override { return rules_tick_; }
  double rules_dt() const override { return dt_; }
  const std::vector<ClientGameMessage>& rules_messages() const override { return delivering_; }
  void rules_added(phys::BodyId id, const phys::BodyDef& def) override { note_added(id, def); }
  void rules_removed(phys::BodyId id) override { note_removed(id); }
  void rules_set(phys::BodyId id, std::optional<phys::Vec2> position,
                 std::optional<phys::Vec2> velocity,
                 std::optional<phys::Vec2> acceleration) override;
  void rules_send(OutgoingGameMessage message) override { outgoing_.push_back(std::move(message)); }

  // A body added or removed, for snapshots (take_changes) and the relay.
  void note_added(phys::BodyId body, const phys::BodyDef& def);
  void note_removed(phys::BodyId body);
  // The game state to the relay when it differs from the last sent.
  void relay_game_state();

  scene::SceneDef scene_;
  SimulationOptions options_;
  double tick_rate_;
  double dt_;
  phys::World world_;
  Room room_;
  std::map<ClientId, ClientInputs> inputs_;
  std::uint64_t current_tick_ = 0;
  BodyChanges changes_;
  std::unique_ptr<TickRecorder> recorder_;
  RelayLog* relay_ = nullptr;
  std::shared_ptr<GameRules> rules_;
  std::uint64_t rules_tick_ = 0;  // GameWorld::tick() in the rules' callbacks
  // Game messages waiting for their tick (ascending tick, then client), and the
  // ones of the tick being stepped (GameWorld::messages).
  std::map<std::uint64_t, std::map<ClientId, std::vector<std::string>>> game_messages_;
  std::vector<ClientGameMessage> delivering_;
  std::vector<OutgoingGameMessage> outgoing_;
  std::map<ClientId, phys::Vec2> last_applied_;  // each player's last input the rules saw
  phys::GameState relayed_game_state_;           // the last one the relay was given
  bool ended_ = false;
};

}  // namespace server
