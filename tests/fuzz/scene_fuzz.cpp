// libFuzzer harness: scene text, as a user's --scene file is read. The loader
// (parse_scene_text: Protobuf text format, then every check of the scene checker)
// must refuse bad text with a SceneError, never crash; a scene it accepts must build
// into a World and step (a scene the core refuses after the loader accepted it is a
// loader bug: build_world's std::invalid_argument is not caught here, so it fails).
// Covered: shared/scene (text parser, field paths, checker, build_world) and the
// first steps of the core on what it builds. Not covered: load_scene_file's file
// size check and file reading, which tests/scene covers.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <variant>

#include "physics/world.h"
#include "scene/scene.h"

namespace {
// Scenes this large are valid but would make one input take seconds to build and
// step; the loader's own limits are tested in tests/scene.
constexpr std::size_t kMaxBodiesToStep = 2000;
constexpr int kSteps = 3;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  scene::SceneResult result = scene::parse_scene_text(text, "fuzz.textproto");
  if (const auto* error = std::get_if<scene::SceneError>(&result)) {
    (void)error->to_string();
    return 0;
  }
  const scene::SceneDef& def = std::get<scene::SceneDef>(result);
  if (def.bodies.size() > kMaxBodiesToStep) return 0;
  phys::World world = scene::build_world(def);
  const double dt = scene::fixed_dt(def);
  for (int i = 0; i < kSteps; ++i) world.step(dt);
  (void)world.state_hash();
  return 0;
}
