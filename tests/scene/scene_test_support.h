#pragma once
// Helpers for the scene tests: parse text that must be refused, and where the
// repository's scenes/ folder is.
#include <gtest/gtest.h>

#include <filesystem>
#include <string_view>
#include <variant>

#include "scene/scene.h"

namespace scene::testing {

inline std::filesystem::path scenes_dir() { return PHYSICS_SCENES_DIR; }

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
