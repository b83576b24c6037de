// Rules built for another layout of the entry point's answer (a later plugin ABI).
#include <memory>

#include "server/rules_plugin.h"

namespace {

std::shared_ptr<server::GameRules> make_rules(const scene::SceneDef& /*scene*/) {
  return std::make_shared<server::GameRules>();
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const server::RulesPluginInfo*
physics_game_rules_v1() {
  static const server::RulesPluginInfo info{PHYSICS_RULES_PLUGIN_ABI + 1, PHYSICS_SERVER_VERSION,
                                            PHYSICS_RULES_STDLIB, &make_rules};
  return &info;
}
