// Goal rush's rules as a library physics-server loads:
//   physics-server --rules libgoal_rush.so --scene goal-rush.textproto
#include <memory>

#include "goal_rush_rules.h"
#include "server/rules_plugin.h"

namespace {

std::shared_ptr<server::GameRules> make_goal_rush_rules(const scene::SceneDef& scene) {
  return std::make_shared<goal_rush::GoalRushRules>(scene.player);
}

}  // namespace

PHYSICS_GAME_RULES(make_goal_rush_rules)
