#pragma once
// physics-server's command line, for any program that serves a game: every flag of
// physics-server (docs/SERVER.md, "Running it"), --help, the "listening on
// ADDRESS:PORT" line on stdout, the log on stderr, and its exit codes: 0 a clean
// shutdown, 1 the server failed while running or could not listen, 2 bad flags, a bad
// scene file or rules that could not be made. A game's own server program is then
//
//   int main(int argc, char** argv) {
//     server::ServerProgram program{"my-game-server", "My game on the physics server"};
//     program.rules = [](const scene::SceneDef& scene) { return std::make_shared<MyRules>(); };
//     program.default_scene = "my-game.textproto";
//     return server::run_server_cli(argc, argv, program);
//   }
#include <functional>
#include <memory>
#include <string>

#include "scene/scene.h"
#include "server/game_rules.h"

namespace server {

struct ServerProgram {
  // Its name, in --help and in front of every error message.
  std::string name = "physics-server";
  std::string description =
      "physics-server: an authoritative 2D physics server speaking Protobuf over TCP";
  // Set: the game's rules, made for the scene loaded, and no --rules flag. Unset:
  // --rules FILE loads them from a rules library (server/rules_plugin.h), and without
  // it there are none.
  std::function<std::shared_ptr<GameRules>(const scene::SceneDef&)> rules;
  // Set: the scene file served without --scene. Unset: the built-in scene.
  std::string default_scene;
};

// Parses the flags, serves until SIGINT or SIGTERM (or --shutdown-after-match), and
// returns the exit code.
int run_server_cli(int argc, char** argv, const ServerProgram& program);

}  // namespace server
