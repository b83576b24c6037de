#include "client/game_rules_loader.h"

#include <utility>
#include <variant>

#include "scene/scene.h"
#include "server/rules_library.h"

namespace client {

RulesMaker load_game_rules(const std::string& rules_file, const std::string& scene_file,
                           std::string* error) {
  scene::SceneDef scene = scene::default_scene();
  if (!scene_file.empty()) {
    scene::SceneResult loaded = scene::load_scene_file(scene_file);
    if (const auto* bad = std::get_if<scene::SceneError>(&loaded)) {
      *error = "bad scene: " + bad->to_string();
      return {};
    }
    scene = std::get<scene::SceneDef>(std::move(loaded));
  }
  server::LoadedRules first = server::load_rules_library(rules_file, scene);
  if (!first.rules) {
    *error = first.error;
    return {};
  }
  // The first copy is the first client's; the library stays loaded while any lives.
  return [file = rules_file, scene = std::move(scene),
          spare = std::move(first.rules)]() mutable -> std::shared_ptr<server::GameRules> {
    if (spare) return std::exchange(spare, nullptr);
    return server::load_rules_library(file, scene).rules;
  };
}

}  // namespace client
