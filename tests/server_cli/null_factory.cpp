// Rules whose factory makes nothing.
#include <memory>

#include "server/rules_plugin.h"

namespace {

std::shared_ptr<server::GameRules> make_rules(const scene::SceneDef& /*scene*/) { return nullptr; }

}  // namespace

PHYSICS_GAME_RULES(make_rules)
