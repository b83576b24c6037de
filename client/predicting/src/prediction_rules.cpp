#include "prediction_rules.h"

#include <utility>

#include "server/rules_tick.h"
#include "server/simulation.h"
#include "wire.pb.h"

namespace client {
namespace {

// The rules' host in a predicting client: the core's world and the relay's players.
// The rules' changes need no report (nothing is relayed from here); their messages
// are kept.
class PredictedHost final : public server::RulesHost {
 public:
  PredictedHost(phys::World& world, const std::map<server::ClientId, phys::BodyId>& players,
                std::uint64_t tick, double dt,
                const std::vector<server::ClientGameMessage>& messages,
                std::vector<server::OutgoingGameMessage>& sent)
      : world_(world), players_(players), tick_(tick), dt_(dt), messages_(messages), sent_(sent) {}

  phys::World& rules_world() override { return world_; }
  const phys::World& rules_world() const override { return world_; }
  const std::map<server::ClientId, phys::BodyId>& rules_players() const override {
    return players_;
  }
  std::uint64_t rules_tick() const override { return tick_; }
  double rules_dt() const override { return dt_; }
  const std::vector<server::ClientGameMessage>& rules_messages() const override {
    return messages_;
  }
  void rules_added(phys::BodyId, const phys::BodyDef&) override {}
  void rules_removed(phys::BodyId) override {}
  void rules_set(phys::BodyId, std::optional<phys::Vec2>, std::optional<phys::Vec2>,
                 std::optional<phys::Vec2>) override {}
  void rules_send(server::OutgoingGameMessage message) override {
    sent_.push_back(std::move(message));
  }

 private:
  phys::World& world_;
  const std::map<server::ClientId, phys::BodyId>& players_;
  std::uint64_t tick_;
  double dt_;
  const std::vector<server::ClientGameMessage>& messages_;
  std::vector<server::OutgoingGameMessage>& sent_;
};

const std::vector<server::ClientGameMessage> kNoMessages;

}  // namespace

PredictionRules::PredictionRules(std::shared_ptr<server::GameRules> rules)
    : rules_(std::move(rules)) {}

void PredictionRules::reset(const std::vector<Player>& players, std::uint32_t own_client) {
  players_.clear();
  for (const Player& player : players) {
    players_[player.client_id] = phys::BodyId::from_packed(player.body_id);
  }
  own_client_ = own_client;
}

void PredictionRules::apply_players(const physics::wire::RelayTick& relay) {
  // Client ids are never used twice, so joins and leaves can be taken in this order
  // even when the world the core started from already held some of them.
  for (const physics::wire::RelayPlayer& player : relay.joined()) {
    players_[player.client_id()] = phys::BodyId::from_packed(player.body_id());
  }
  for (const std::uint32_t client : relay.left()) players_.erase(client);
}

std::string PredictionRules::check(const physics::wire::RelayTick& relay) const {
  for (const physics::wire::RelayRulesInput& input : relay.rules_inputs()) {
    if (players_.count(input.client_id()) == 0) {
      return "relayed tick " + std::to_string(relay.tick()) + " hands the rules an input of " +
             std::to_string(input.client_id()) + ", who is not a player";
    }
  }
  const auto where = [&relay] {
    return "relayed tick " + std::to_string(relay.tick()) + ": a game message";
  };
  std::map<std::uint32_t, std::size_t> per_client;
  for (const physics::wire::RelayGameMessage& message : relay.messages()) {
    if (players_.count(message.client_id()) == 0) {
      return where() + " of " + std::to_string(message.client_id()) + ", who is not a player";
    }
    if (message.payload().size() > server::kMaxGameMessageBytes) {
      return where() + " of " + std::to_string(message.payload().size()) + " bytes, over the " +
             std::to_string(server::kMaxGameMessageBytes) + " the server takes";
    }
    if (++per_client[message.client_id()] > server::kMaxGameMessagesPerTick) {
      return where() + " over the " + std::to_string(server::kMaxGameMessagesPerTick) +
             " a client may send for one tick";
    }
  }
  return {};
}

RulesTickInputs PredictionRules::confirmed(const physics::wire::RelayTick& relay) const {
  RulesTickInputs in;
  for (const physics::wire::RelayRulesInput& input : relay.rules_inputs()) {
    in.inputs.push_back(
        {input.client_id(), players_.at(input.client_id()), {input.ax(), input.ay()}});
  }
  for (const physics::wire::RelayGameMessage& message : relay.messages()) {
    in.messages.push_back({message.client_id(), message.payload()});
  }
  return in;
}

std::optional<phys::Vec2> PredictionRules::own_input_after(const physics::wire::RelayTick& relay,
                                                           std::optional<phys::Vec2> before) const {
  for (const physics::wire::RelayRulesInput& input : relay.rules_inputs()) {
    if (input.client_id() == own_client_) before = phys::Vec2{input.ax(), input.ay()};
  }
  return before;
}

RulesTickInputs PredictionRules::predicted(std::optional<phys::Vec2> fresh_input,
                                           std::optional<phys::Vec2> last_seen,
                                           phys::BodyId own_body,
                                           const std::vector<std::string>& own_messages) const {
  RulesTickInputs in;
  if (own_client_ == 0 || players_.count(own_client_) == 0) return in;
  // The server lists a player's input when it is the first or differs from the last.
  if (fresh_input && (!last_seen || !(*last_seen == *fresh_input))) {
    in.inputs.push_back({own_client_, own_body, *fresh_input});
  }
  for (const std::string& payload : own_messages) in.messages.push_back({own_client_, payload});
  return in;
}

bool PredictionRules::same(const physics::wire::RelayTick& relay,
                           const RulesTickInputs& predicted) const {
  if (relay.rules_inputs_size() != static_cast<int>(predicted.inputs.size()) ||
      relay.messages_size() != static_cast<int>(predicted.messages.size())) {
    return false;
  }
  for (std::size_t i = 0; i < predicted.inputs.size(); ++i) {
    const auto& relayed = relay.rules_inputs(static_cast<int>(i));
    const server::AppliedInput& mine = predicted.inputs[i];
    if (relayed.client_id() != mine.client ||
        !(phys::Vec2{relayed.ax(), relayed.ay()} == mine.acceleration)) {
      return false;
    }
  }
  for (std::size_t i = 0; i < predicted.messages.size(); ++i) {
    const auto& relayed = relay.messages(static_cast<int>(i));
    if (relayed.client_id() != predicted.messages[i].client ||
        relayed.payload() != predicted.messages[i].payload) {
      return false;
    }
  }
  return true;
}

void PredictionRules::before_step(phys::World& world, std::uint64_t tick, double dt,
                                  const RulesTickInputs& in,
                                  std::vector<server::OutgoingGameMessage>& sent) {
  PredictedHost host(world, players_, tick, dt, in.messages, sent);
  server::run_rules_before_step(*rules_, host, tick, in.inputs);
}

void PredictionRules::after_step(phys::World& world, std::uint64_t tick, double dt,
                                 std::vector<server::OutgoingGameMessage>& sent) {
  PredictedHost host(world, players_, tick, dt, kNoMessages, sent);
  server::run_rules_after_step(*rules_, host);
}

}  // namespace client
