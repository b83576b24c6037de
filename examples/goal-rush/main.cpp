// goal-rush-server: physics-server with goal rush's rules built in, serving the
// goal-rush.textproto beside this file unless told another --scene. Every flag of
// physics-server (goal-rush-server --help). physics-server --rules libgoal_rush.so
// serves the same game without a program of its own.
#include "goal_rush_rules.h"
#include "server/server_cli.h"

int main(int argc, char** argv) {
  server::ServerProgram program;
  program.name = "goal-rush-server";
  program.description = "goal-rush-server: goal rush on the physics server";
  program.rules = [](const scene::SceneDef& scene) {
    return std::make_shared<goal_rush::GoalRushRules>(scene.player);
  };
  program.default_scene = GOAL_RUSH_SCENE;
  return server::run_server_cli(argc, argv, program);
}
