#pragma once
// Helpers for the scene tests: a valid scene to add one bad thing to, parse text
// that must be refused, and where the repository's scenes/ folder is.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <variant>

#include "scene/scene.h"

namespace scene::testing {

inline std::filesystem::path scenes_dir() { return PHYSICS_SCENES_DIR; }

// A valid scene; each bad-scene test appends or replaces one thing. Line numbers in
// the tests count from the first line of the test's own text.
constexpr std::string_view kWorld =
    "world { bounds { min { x: -10 y: -10 } max { x: 10 y: 10 } } }\n";
constexpr std::string_view kSpawn = "spawn_points { x: 1 y: 1 }\n";

inline std::string scene_with(std::string_view bodies) {
  return std::string(kWorld) + std::string(bodies) + std::string(kSpawn);
}

// The error for text that must be refused; a test failure when it is accepted.
inline SceneError refused(std::string_view text) {
  SceneResult result = parse_scene_text(text, "test.textproto");
  if (const auto* error = std::get_if<SceneError>(&result)) return *error;
  ADD_FAILURE() << "scene was accepted:\n" << text;
  return {};
}

inline SceneDef accepted(std::string_view text) {
  SceneResult result = parse_scene_text(text, "test.textproto");
  if (const auto* error = std::get_if<SceneError>(&result)) {
    ADD_FAILURE() << "scene was refused: " << error->to_string() << "\n" << text;
    return {};
  }
  return std::get<SceneDef>(std::move(result));
}

}  // namespace scene::testing
