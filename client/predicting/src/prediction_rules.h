#pragma once
// The game's rules inside the rollback (PredictionCore::set_rules): on every tick the
// core steps, confirmed or predicted, the rules are called as the server's Simulation
// calls them (server/rules_tick.h), on the core's world, with the players of the
// relay and the inputs and game messages of that tick:
//   - a confirmed tick: the relay's lists (RelayTick.rules_inputs, messages);
//   - a predicted tick: the own input when it changes (as the server lists it) and
//     the own game messages sent for that tick; no other player's.
// What the rules send (GameWorld::send, broadcast) is kept for predicted ticks only:
// the server sends the confirmed ones.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "client/types.h"
#include "physics/world.h"
#include "server/game_rules.h"

namespace physics::wire {
class RelayTick;
}

namespace client {

// What the rules are handed at one tick.
struct RulesTickInputs {
  std::vector<server::AppliedInput> inputs;
  std::vector<server::ClientGameMessage> messages;
};

class PredictionRules {
 public:
  explicit PredictionRules(std::shared_ptr<server::GameRules> rules);

  // The players of the world the core starts from (Welcome::players).
  void reset(const std::vector<Player>& players, std::uint32_t own_client);
  const std::map<server::ClientId, phys::BodyId>& players() const { return players_; }
  bool wants_contact_events() const { return rules_->wants_contact_events(); }

  // A relayed tick's players who joined and left, applied to the players.
  void apply_players(const physics::wire::RelayTick& relay);
  // Why a relayed tick's rules lists cannot be the server's (a message or an input
  // of a client that is not a player, a message over the limits), or empty.
  std::string check(const physics::wire::RelayTick& relay) const;
  // The relay's lists, with each player's body.
  RulesTickInputs confirmed(const physics::wire::RelayTick& relay) const;
  // The own client's input the rules last saw after the relayed tick (nullopt: none).
  std::optional<phys::Vec2> own_input_after(const physics::wire::RelayTick& relay,
                                            std::optional<phys::Vec2> before) const;
  // The prediction of a tick: the own input when it differs from `last_seen` (the
  // own input the rules saw last), and the own messages of the tick.
  RulesTickInputs predicted(std::optional<phys::Vec2> fresh_input,
                            std::optional<phys::Vec2> last_seen, phys::BodyId own_body,
                            const std::vector<std::string>& own_messages) const;
  // Whether the relay's lists are the predicted ones.
  bool same(const physics::wire::RelayTick& relay, const RulesTickInputs& predicted) const;

  // The rules' calls around the world's step; the messages the rules sent go to `sent`.
  void before_step(phys::World& world, std::uint64_t tick, double dt, const RulesTickInputs& in,
                   std::vector<server::OutgoingGameMessage>& sent);
  void after_step(phys::World& world, std::uint64_t tick, double dt,
                  std::vector<server::OutgoingGameMessage>& sent);

  std::uint32_t own_client() const { return own_client_; }

 private:
  std::shared_ptr<server::GameRules> rules_;
  std::map<server::ClientId, phys::BodyId> players_;
  std::uint32_t own_client_ = 0;
};

}  // namespace client
