#pragma once
// A game's rules library (server/rules_plugin.h, the one physics-server --rules
// runs), made for the game's scene, to run in a predicting client
// (PredictingClientConfig::rules): physics-client and physics-view --predict --rules
// FILE [--scene FILE]. A program that loads one exports its symbols to it and links
// the rules' API whole, as physics-server does (server/rules_library.h).
#include <functional>
#include <memory>
#include <string>

#include "server/game_rules.h"

namespace client {

using RulesMaker = std::function<std::shared_ptr<server::GameRules>()>;

// Loads the scene (empty: the built-in one) and the library once to check both; the
// maker then makes a fresh copy of the rules for each client. Empty, and *error
// says why, when either cannot be loaded.
RulesMaker load_game_rules(const std::string& rules_file, const std::string& scene_file,
                           std::string* error);

}  // namespace client
