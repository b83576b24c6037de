// A shared library without physics-server's entry point: rules whose author forgot
// PHYSICS_GAME_RULES.
#include <memory>

#include "server/game_rules.h"

__attribute__((visibility("default"))) std::shared_ptr<server::GameRules> make_rules() {
  return std::make_shared<server::GameRules>();
}
