// Rules for the viewers' tests, as a library physics-server loads (--rules): every
// game message is answered to its sender, "got <payload>", stamped with the tick it
// was delivered at. The browser viewer's test (client/web/viewer/test) presses a key
// bound to a message and finds the answer in its panel.
#include <memory>
#include <string>
#include <vector>

#include "server/rules_plugin.h"

namespace {

class EchoRules : public server::GameRules {
 public:
  void before_step(server::GameWorld& world,
                   const std::vector<server::AppliedInput>& /*inputs*/) override {
    for (const server::ClientGameMessage& message : world.messages())
      world.send(message.client, "got " + message.payload);
  }
};

std::shared_ptr<server::GameRules> make_echo_rules(const scene::SceneDef& /*scene*/) {
  return std::make_shared<EchoRules>();
}

}  // namespace

PHYSICS_GAME_RULES(make_echo_rules)
