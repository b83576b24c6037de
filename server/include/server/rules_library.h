#pragma once
// Loads a game's rules from a shared library (server/rules_plugin.h): what
// `physics-server --rules FILE` does, for any program that hosts rules libraries.
// The program must export its symbols to the libraries it loads (CMake:
// ENABLE_EXPORTS, with the rules' API linked whole; docs/SERVER.md, "Your game on
// the server"), since the rules link none of the server's code themselves.
#include <filesystem>
#include <memory>
#include <string>

#include "scene/scene.h"
#include "server/game_rules.h"

namespace server {

struct LoadedRules {
  // Set: the rules, made for the scene. The library stays loaded while they live.
  std::shared_ptr<GameRules> rules;
  // Otherwise why not, naming the file: it does not exist, is not a shared library
  // (the dynamic loader's message), has no entry point, was built against another
  // version of the package or another C++ standard library, or its factory threw or
  // made nothing.
  std::string error;
};

LoadedRules load_rules_library(const std::filesystem::path& file, const scene::SceneDef& scene);

}  // namespace server
