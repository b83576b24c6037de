// goal-rush-server: the physics server with goal rush's rules, on the scene beside it.
//   goal-rush-server [PORT [SCENE]]    (defaults: 7777, the goal-rush.textproto beside this file)
// Players join with any client (physics-client, physics-view, your own); physics-view
// draws it: `physics-view --port PORT`. Ctrl-C stops it.
#include <charconv>
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>
#include <variant>

#include "goal_rush_rules.h"
#include "scene/scene.h"
#include "server/server.h"

int main(int argc, char** argv) {
  std::uint16_t port = 7777;
  if (argc > 1) {
    const std::string text = argv[1];
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), port);
    if (error != std::errc{} || end != text.data() + text.size()) {
      std::cerr << "goal-rush-server: the port must be a number in [0, 65535], got '" << text
                << "'\n";
      return 2;
    }
  }
  const std::string scene_file = argc > 2 ? argv[2] : GOAL_RUSH_SCENE;
  scene::SceneResult loaded = scene::load_scene_file(scene_file);
  if (const auto* error = std::get_if<scene::SceneError>(&loaded)) {
    std::cerr << "goal-rush-server: " << error->to_string() << "\n";
    return 1;
  }
  auto& scene = std::get<scene::SceneDef>(loaded);

  server::ServerConfig config;
  config.port = port;
  config.rules = std::make_shared<goal_rush::GoalRushRules>(scene.player);
  config.handle_signals = true;  // SIGINT and SIGTERM stop it
  server::Server server(config, scene);
  std::cout << "goal rush on port " << server.port() << std::endl;
  server.run();
  return 0;
}
