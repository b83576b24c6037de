// Rules whose factory refuses the scene it is given.
#include <memory>
#include <stdexcept>

#include "server/rules_plugin.h"

namespace {

std::shared_ptr<server::GameRules> make_rules(const scene::SceneDef& scene) {
  throw std::runtime_error("this game needs a scene named 'arena', not '" + scene.name + "'");
}

}  // namespace

PHYSICS_GAME_RULES(make_rules)
