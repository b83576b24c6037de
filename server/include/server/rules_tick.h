#pragma once
// The rules' part of a tick, in the order game_rules.h gives: the timers due at the
// tick (on_timer, in (due, name, index) order), then before_step; after the world's
// step, after_step. The server's Simulation and a predicting client that runs the
// rules (client/prediction_core.h) both call these, so that both make the same calls
// in the same order on the same world.
#include <cstdint>
#include <vector>

#include "server/game_rules.h"

namespace server {

void run_rules_before_step(GameRules& rules, RulesHost& host, std::uint64_t tick,
                           const std::vector<AppliedInput>& inputs);
void run_rules_after_step(GameRules& rules, RulesHost& host);

}  // namespace server
