#pragma once
// A game's rules as a shared library that physics-server loads: `physics-server
// --rules libmygame.so --scene mygame.textproto`, with every flag of physics-server.
// The library defines its one entry point with PHYSICS_GAME_RULES, in one of its
// source files:
//
//   #include "server/rules_plugin.h"
//   std::shared_ptr<server::GameRules> make_my_rules(const scene::SceneDef& scene) {
//     return std::make_shared<MyRules>(scene.player);
//   }
//   PHYSICS_GAME_RULES(make_my_rules)
//
// and is built with physics_add_game_rules(TARGET SOURCES...) of the installed
// package (docs/SERVER.md, "Your game on the server"). The library links none of the
// server's code: the rules use the GameWorld, GameRules and physics types of the
// physics-server that loads them (its symbols are exported to the libraries it
// loads), so that there is one copy of each. It must therefore be built against the
// same version of the package, with the same C++ standard library; physics-server
// checks both before it calls anything else of the library.
#include <cstdint>
#include <memory>

#include "scene/scene.h"
#include "server/game_rules.h"
#include "server/version.h"

// The layout of RulesPluginInfo and the meaning of its fields; a library built for
// another layout is refused before its factory is called.
#define PHYSICS_RULES_PLUGIN_ABI 1

// The C++ standard library the code was built with: a std::string or std::shared_ptr
// crosses between the library and the server, so both must lay them out alike.
#if defined(_LIBCPP_VERSION)
#define PHYSICS_RULES_STDLIB "libc++"
#elif defined(_GLIBCXX_USE_CXX11_ABI) && _GLIBCXX_USE_CXX11_ABI
#define PHYSICS_RULES_STDLIB "libstdc++ (C++11 ABI)"
#else
#define PHYSICS_RULES_STDLIB "libstdc++ (old ABI)"
#endif

// The entry point's name, for dlsym.
#define PHYSICS_GAME_RULES_ENTRY_POINT "physics_game_rules_v1"

namespace server {

// Makes the rules for the scene physics-server loaded (--scene, or the built-in
// one). May throw: physics-server reports the exception and exits 2.
using RulesFactory = std::shared_ptr<GameRules> (*)(const scene::SceneDef& scene);

// What the entry point returns. `plugin_abi` comes first and stays first in every
// layout, so that any library's can be read.
struct RulesPluginInfo {
  std::uint32_t plugin_abi = 0;       // PHYSICS_RULES_PLUGIN_ABI
  const char* package_version = "";   // PHYSICS_SERVER_VERSION
  const char* standard_library = "";  // PHYSICS_RULES_STDLIB
  RulesFactory make_rules = nullptr;
};

}  // namespace server

// The entry point, defined by PHYSICS_GAME_RULES in the game's library.
extern "C" const server::RulesPluginInfo* physics_game_rules_v1();

// Defines the entry point: `factory` is a function
// std::shared_ptr<server::GameRules>(const scene::SceneDef&).
#define PHYSICS_GAME_RULES(factory)                                                               \
  extern "C" __attribute__((visibility("default"))) const ::server::RulesPluginInfo*              \
  physics_game_rules_v1() {                                                                       \
    static const ::server::RulesPluginInfo info{PHYSICS_RULES_PLUGIN_ABI, PHYSICS_SERVER_VERSION, \
                                                PHYSICS_RULES_STDLIB, &(factory)};                \
    return &info;                                                                                 \
  }
