// physics-flatten: a scene file as a flat world (portable/flat_world.h), the numbers a
// build without Protobuf loads: physics-hashes on AArch64 and WebAssembly, and the
// WebAssembly core package (client/web/core-wasm).
//   physics-flatten SCENE.textproto [OUT.json]   (stdout without OUT)
//   physics-flatten --rain N [OUT.json]          the bench's rain-N (scene library)
// Exit codes: 0 written, 2 bad arguments, a bad scene or an unwritable file.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <variant>

#include "portable/flat_world.h"
#include "scene/scene.h"
#include "scenes/scenes.h"

int main(int argc, char** argv) {
  constexpr int kExitBadInput = 2;
  constexpr const char* kUsage =
      "usage: physics-flatten SCENE.textproto [OUT.json]   the scene as a flat world (JSON)\n"
      "       physics-flatten --rain N [OUT.json]          the bench's rain-N, N in [1, 100000]\n";
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  portable::FlatWorld flat;
  int out_arg = 2;
  if (argc >= 3 && argc <= 4 && std::string(argv[1]) == "--rain") {
    char* end = nullptr;
    const long count = std::strtol(argv[2], &end, 10);
    if (*argv[2] == '\0' || *end != '\0' || count < 1 || count > 100000) {
      std::fputs(kUsage, stderr);
      return kExitBadInput;
    }
    // As the bench and the scene library's goldens run it: default settings, the
    // scene's gravity and dt.
    const scenes::SceneSpec rain = scenes::rain_scene(static_cast<int>(count), 1, 0, 0);
    flat.settings.gravity = rain.gravity;
    flat.dt = rain.dt;
    for (const scenes::BodySpec& body : rain.bodies)
      flat.bodies.push_back(scenes::to_body_def(body));
    out_arg = 3;
  } else if (argc >= 2 && argc <= 3 && std::string(argv[1]).rfind('-', 0) != 0) {
    scene::SceneResult loaded = scene::load_scene_file(argv[1]);
    if (const auto* error = std::get_if<scene::SceneError>(&loaded)) {
      std::fprintf(stderr, "%s\n", error->to_string().c_str());
      return kExitBadInput;
    }
    const scene::SceneDef& def = std::get<scene::SceneDef>(loaded);
    flat = {def.world, scene::fixed_dt(def), def.bodies};
  } else {
    std::fputs(kUsage, stderr);
    return kExitBadInput;
  }
  const std::string json = portable::to_json(portable::flatten(flat));
  if (argc == out_arg) {
    std::fputs(json.c_str(), stdout);
    return 0;
  }
  std::ofstream out(argv[out_arg], std::ios::binary);
  out << json;
  out.close();
  if (!out) {
    std::fprintf(stderr, "physics-flatten: cannot write %s\n", argv[out_arg]);
    return kExitBadInput;
  }
  return 0;
}
