#include "server/rules_tick.h"

#include <optional>

namespace server {

void run_rules_before_step(GameRules& rules, RulesHost& host, std::uint64_t tick,
                           const std::vector<AppliedInput>& inputs) {
  GameWorld handle(host);
  phys::GameState& state = host.rules_world().game_state();
  for (const phys::GameKey& key : state.timers_due(tick)) {
    // An earlier timer's rule may have cancelled this one, or started it again later.
    const std::optional<phys::GameTimer> timer = state.timer(key.name, key.index);
    if (!timer || timer->due > tick) continue;
    state.fired(key, tick);
    rules.on_timer(handle, key.name, key.index);
  }
  rules.before_step(handle, inputs);
}

void run_rules_after_step(GameRules& rules, RulesHost& host) {
  GameWorld handle(host);
  rules.after_step(handle);
}

}  // namespace server
