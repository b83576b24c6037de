#pragma once
// The rollback loop of a predicting client (GGPO's, around the physics core's save
// and restore), with no sockets and no clock: the Welcome's world and every
// snapshot's relay go in, the own inputs go in, and the world comes out predicted to
// the present tick. PredictingClient (predicting_client.h) drives it over a
// connection; tests drive it with messages made in-process.
//
// Two states are kept: the confirmed one (the server's relayed ticks applied, up to
// tick C) and the predicted world at tick P > C, stepped with the own input of each
// tick and every other body's acceleration held (what the world does when nothing
// is set). Each predicted tick's state is saved in a ring. When the relay of C + 1
// arrives:
//   - equal to what was predicted (no body added or removed, no other body's
//     acceleration changed, the own acceleration the one predicted): the saved state
//     of C + 1 becomes the confirmed one. Nothing is stepped again.
//   - different: the world is restored to C, every relayed tick is applied, and the
//     prediction is stepped again up to P (a rollback of P - C ticks).
// The prediction runs at most max_rollback ticks past C (GGPO's prediction
// barrier): beyond it, it waits for the server, so that no rollback is deeper.
//
// The relay's state hash is compared with the confirmed state's; a mismatch, a
// change that does not apply (a join whose id is taken or differs from the server's,
// a leave of an unknown body, an input for a body without one), a gap in the ticks
// relayed: each is counted, and a full state is asked for (take_full_state_request)
// and applied when Snapshot::world_state answers. Ticks at or before C are counted
// and ignored. When max_failed_resyncs full states in a row are followed by a
// mismatch, the core stops (failed(), error()): the server's core is not this one.
//
// With the game's rules (set_rules), the rules run on every tick stepped, confirmed
// or predicted, as the server runs them (prediction_rules.h): a confirmed tick hands
// them the relay's inputs and game messages, a predicted one the own input and the
// own game messages of that tick (send_message), so the own message's effect is in
// the next predicted tick as the own input's is. A relayed tick then matches the
// prediction when, besides the above, the rules were handed the same inputs and
// messages; another player's message is a difference, and a rollback. The relay must
// be the one for clients that run the rules (ClientConfig::run_rules,
// Welcome::rules_run_here), which carries no rules' changes.
//
// Corrections are smoothed for the eye (Overwatch, Rocket League): a body's
// position error after a rollback, old prediction minus new, is added to what
// render() shows and decays as exp(-t / smoothing_time_constant), t counted in
// ticks advanced, so 0.1 s is 6 ticks at 60 Hz; an error over snap_distance is
// shown at once. predicted_world() is the raw prediction.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "client/types.h"
#include "physics/world.h"
#include "server/game_rules.h"

namespace physics::wire {
class RelayTick;
}

namespace client {

class PredictionRules;

struct PredictionConfig {
  // The deepest rollback, in ticks: the prediction runs at most this far past the
  // confirmed tick (0: no prediction, the world shown is the confirmed one).
  std::uint32_t max_rollback = 30;
  // s: a correction decays to 1/e of itself in this time.
  double smoothing_time_constant = 0.1;
  // m: a correction larger than this is shown at once (a teleport, a resync).
  double snap_distance = 2.0;
  // Full states applied in a row, each followed by a hash mismatch, before the core
  // gives up.
  std::uint32_t max_failed_resyncs = 3;
};

struct PredictionStats {
  std::uint64_t confirmed_ticks = 0;  // relayed ticks taken
  std::uint64_t matched_ticks = 0;    // of them, equal to the prediction: no rollback
  std::uint64_t rollbacks = 0;
  std::uint64_t resimulated_ticks = 0;  // steps of ticks that had been stepped before
  std::uint64_t predicted_ticks = 0;    // steps of ticks stepped for the first time
  std::uint64_t barrier_waits = 0;      // advance_to calls held back by max_rollback
  std::uint64_t hashes_checked = 0;
  std::uint64_t desyncs = 0;  // state hashes that differed from ours
  std::uint64_t full_state_requests = 0;
  std::uint64_t resyncs = 0;           // full states applied
  std::uint64_t bad_changes = 0;       // relayed changes or inputs that did not apply
  std::uint64_t stale_ticks = 0;       // relayed ticks at or before the confirmed one
  std::uint64_t gaps = 0;              // relayed ticks after a missing one
  std::uint64_t deep_rollbacks = 0;    // a rollback deeper than max_rollback asked for
  std::uint64_t bad_world_states = 0;  // world states that did not parse
  std::uint64_t rules_errors = 0;      // ticks whose rules threw (a full state asked for)
  std::uint64_t ticks_dropped = 0;     // relayed while a full state was awaited
  // m: the largest jump of a body's predicted position a rollback caused, and the
  // largest a rendered body was moved in one tick by the smoothing of corrections.
  double largest_correction = 0.0;
  double largest_smoothed_correction = 0.0;
};

// A body as render() shows it: the predicted position plus the correction still
// decaying, and the raw predicted one.
struct RenderBody {
  std::uint64_t body_id = 0;
  Vec2 position;
  Vec2 velocity;
  Vec2 predicted_position;
  Motion motion = Motion::Dynamic;  // Dynamic or Kinematic (static bodies never move)
};

struct RenderState {
  std::uint64_t tick = 0;          // the predicted tick shown
  std::vector<RenderBody> bodies;  // every moving (dynamic or kinematic) body, ascending id
};

class PredictionCore {
 public:
  explicit PredictionCore(PredictionConfig config = {});

  // The game's rules, the same as the server's (a GameRules of the same game, made
  // for the same scene): set before start. nullptr: none.
  void set_rules(std::shared_ptr<server::GameRules> rules);
  bool runs_rules() const { return rules_ != nullptr; }

  // Starts from a Welcome with world_state (ClientConfig::want_world). False, and
  // error() says why, when the bytes are not a world, or the core runs rules and the
  // server did not grant it (Welcome::rules_run_here).
  bool start(const Welcome& welcome);
  // Starts from a world after `tick` (tests; a world built without bytes).
  // own_body 0: no body of our own (a spectator). max_acceleration: the scene's
  // input limit (Welcome::max_acceleration); 0, none. With rules: the players in the
  // world, and the own client id.
  void start(phys::World world, std::uint64_t tick, std::uint64_t own_body, double tick_rate,
             double max_acceleration = 0.0, const std::vector<Player>& players = {},
             std::uint32_t own_client = 0);

  // The own body's acceleration from `tick` on (held until the next), as sent to
  // the server, clamped to the scene's max_acceleration as the server's input check
  // clamps it (phys::clamp_length): an input over the limit is predicted as the
  // server applies it, so its confirmation matches. Inputs for ticks at or before
  // the confirmed one change nothing.
  void set_input(std::uint64_t tick, Vec2 acceleration);
  // The own game message for `tick`, as sent to the server: with rules, handed to
  // them at that tick of the prediction. Messages for confirmed ticks change nothing.
  void send_message(std::uint64_t tick, std::string payload);
  // What the rules sent in the predicted ticks (after confirmed_tick(), up to
  // predicted_tick()), oldest first: the prediction of the server's game messages,
  // which replace them once their tick is confirmed (Client::take_game_messages).
  std::vector<server::OutgoingGameMessage> predicted_messages() const;
  // Takes a snapshot's world state (a full state answered) and relayed ticks.
  void on_snapshot(const Snapshot& snapshot);
  // Predicts up to `tick` (the newest tick whose input was given), or as far as
  // max_rollback allows.
  void advance_to(std::uint64_t tick);

  // True once after a problem asked for a full state: the caller sends a
  // FullStateRequest. Until Snapshot::world_state arrives, relayed ticks are dropped.
  bool take_full_state_request();
  bool awaiting_full_state() const { return awaiting_full_state_; }

  bool started() const { return started_; }
  bool failed() const { return failed_; }
  // Why the core failed, or the last problem counted (for a person).
  const std::string& error() const { return error_; }

  std::uint64_t confirmed_tick() const { return confirmed_tick_; }
  std::uint64_t predicted_tick() const { return world_tick_; }
  std::uint64_t own_body() const { return own_; }
  double dt() const { return dt_; }
  // The raw prediction, at predicted_tick().
  const phys::World& predicted_world() const { return world_; }
  // The confirmed state's hash (World::state_hash), and a world in that state.
  std::uint64_t confirmed_hash();
  phys::World confirmed_world() const;
  // The prediction with the corrections still decaying added.
  RenderState render() const;
  // The correction still added to a body's shown position (zero when none).
  Vec2 correction(std::uint64_t body_id) const;
  const PredictionStats& stats() const { return stats_; }
  const PredictionConfig& config() const { return config_; }

 private:
  struct Slot {
    std::uint64_t tick = 0;
    phys::SavedWorld saved;         // the world after `tick`, predicted
    phys::Vec2 own_acceleration{};  // the own body's, as predicted for `tick`
    // With rules: the own input the rules saw last, after `tick`; what they were
    // handed at `tick` and what they sent.
    std::optional<phys::Vec2> own_rules_input;
    std::vector<server::AppliedInput> rules_inputs;
    std::vector<server::ClientGameMessage> rules_messages;
    std::vector<server::OutgoingGameMessage> sent;
  };
  struct Position {
    std::uint64_t id;
    phys::Vec2 position;
  };

  void begin(phys::World world, std::uint64_t tick);
  Slot& slot(std::uint64_t tick);
  bool matches(const physics::wire::RelayTick& relay) const;
  void confirm_predicted(const physics::wire::RelayTick& relay);
  // Applies one relayed tick to the world at tick - 1 (relay::apply_changes_and_inputs)
  // and steps; false and a full state asked for when a change or an input does not
  // apply.
  bool apply(const physics::wire::RelayTick& relay);
  void step_world();
  // With rules, before_step and after_step around the step; false when they threw.
  bool step_with_rules(const std::vector<server::AppliedInput>& inputs,
                       const std::vector<server::ClientGameMessage>& messages,
                       std::vector<server::OutgoingGameMessage>& sent);
  void predict_to(std::uint64_t tick);
  void predict_one(std::uint64_t tick);
  std::optional<phys::Vec2> own_input_at(std::uint64_t tick) const;
  void check_hash(std::uint64_t tick, std::uint64_t expected, std::uint64_t actual);
  void apply_world_state(std::uint64_t tick, std::span<const std::uint8_t> bytes,
                         const std::vector<Player>& players);
  // The players and the own input the rules last saw, from a Welcome or full state.
  void reset_players(const std::vector<Player>& players);
  void ask_full_state(std::string why);
  void fail(std::string why);
  std::vector<Position> positions() const;
  void add_corrections(const std::vector<Position>& before);
  void decay_corrections(std::uint64_t ticks);
  // Decays the corrections for the ticks the world moved past the newest shown.
  void show_up_to_now();
  void forget_old_inputs();

  PredictionConfig config_;
  std::shared_ptr<PredictionRules> rules_;
  std::uint32_t own_client_ = 0;
  std::optional<phys::Vec2> confirmed_own_rules_input_;
  std::map<std::uint64_t, std::vector<std::string>> own_messages_;  // by tick
  bool started_ = false;
  bool failed_ = false;
  std::string error_;
  double dt_ = 0.0;
  double max_acceleration_ = 0.0;  // the server's input limit; 0: none
  double decay_per_tick_ = 0.0;
  std::uint64_t own_ = 0;
  phys::World world_;           // at world_tick_
  phys::World scratch_;         // the confirmed state, restored to hash it
  phys::SavedWorld confirmed_;  // the world after confirmed_tick_
  std::uint64_t confirmed_tick_ = 0;
  std::uint64_t world_tick_ = 0;
  std::uint64_t target_tick_ = 0;  // the newest tick advance_to asked for
  std::uint64_t frontier_ = 0;     // the newest tick ever stepped
  std::uint64_t shown_tick_ = 0;   // the newest tick render() has shown
  // Moving bodies' positions at compare_tick_ before a rollback: once the world is
  // back at that tick, their differences become corrections.
  std::optional<std::vector<Position>> compare_;
  std::uint64_t compare_tick_ = 0;
  phys::Vec2 confirmed_own_acceleration_{};
  std::vector<Slot> ring_;  // ticks confirmed_tick_ + 1 .. world_tick_, by tick modulo size
  std::map<std::uint64_t, phys::Vec2> inputs_;       // own inputs by tick
  std::map<std::uint64_t, phys::Vec2> corrections_;  // shown minus predicted, by body
  bool awaiting_full_state_ = false;
  bool request_due_ = false;
  bool matched_since_resync_ = true;
  std::uint32_t failed_resyncs_ = 0;
  PredictionStats stats_;
};

}  // namespace client
