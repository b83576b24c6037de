#include "physics_testing/rules_state_check.h"

#include <algorithm>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>

namespace physics_testing {

namespace {

std::string hex(std::uint64_t value) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text = "0x0000000000000000";
  for (int i = 0; i < 16; ++i) text[17 - i] = kDigits[(value >> (4 * i)) & 0xf];
  return text;
}

std::string describe(const server::OutgoingGameMessage& message) {
  return "\"" + message.payload + "\" to " +
         (message.client == 0 ? std::string("everyone")
                              : "player " + std::to_string(message.client));
}

// How the two runs' records of one tick differ ("" when they do not).
std::string difference(const GameTick& kept, const GameTick& fresh) {
  if (kept.state_hash != fresh.state_hash) {
    return "the state hash is " + hex(kept.state_hash) + " with one rules object and " +
           hex(fresh.state_hash) + " with a fresh one before every tick";
  }
  const std::size_t n = std::min(kept.messages.size(), fresh.messages.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (kept.messages[i].client != fresh.messages[i].client ||
        kept.messages[i].payload != fresh.messages[i].payload) {
      return "the rules sent " + describe(kept.messages[i]) + " with one rules object and " +
             describe(fresh.messages[i]) + " with a fresh one before every tick";
    }
  }
  if (kept.messages.size() != fresh.messages.size()) {
    return "the rules sent " + std::to_string(kept.messages.size()) +
           " messages with one rules object and " + std::to_string(fresh.messages.size()) +
           " with a fresh one before every tick";
  }
  return {};
}

std::shared_ptr<server::GameRules> make(const RulesFactory& rules) {
  std::shared_ptr<server::GameRules> made = rules();
  if (!made) throw std::invalid_argument("the rules factory gave no rules");
  return made;
}

}  // namespace

Expected<RulesStateCheck> check_rules_state_in_world(const scene::SceneDef& scene,
                                                     const RulesFactory& rules,
                                                     const GameScript& script,
                                                     std::uint64_t ticks) {
  RulesStateCheck check;
  std::uint64_t tick = 0;
  try {
    GameRun kept(scene, make(rules));
    GameRun fresh(scene, make(rules));
    for (tick = 1; tick <= ticks; ++tick) {
      script(kept, tick);
      const GameTick& kept_tick = kept.step();
      // What the rules know at this tick, they must read from the world.
      fresh.simulation().replace_rules(make(rules));
      script(fresh, tick);
      const GameTick& fresh_tick = fresh.step();
      if (std::string why = difference(kept_tick, fresh_tick); !why.empty()) {
        return Expected<RulesStateCheck>::failure(
            "tick " + std::to_string(tick) + ": " + why +
            ": the rules keep state outside the world (in their own members?)");
      }
      check.hashes.push_back(kept_tick.state_hash);
      check.messages += kept_tick.messages.size();
    }
  } catch (const std::exception& error) {
    return Expected<RulesStateCheck>::failure("tick " + std::to_string(tick) +
                                              ": the run failed: " + error.what());
  }
  return check;
}

}  // namespace physics_testing
