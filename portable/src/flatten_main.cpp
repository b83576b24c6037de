// physics-flatten: a scene file as a flat world (portable/flat_world.h), the numbers a
// build without Protobuf loads: physics-hashes on AArch64 and WebAssembly, and the
// WebAssembly core package (client/web/core-wasm).
//   physics-flatten SCENE.textproto [OUT.json]   (stdout without OUT)
// Exit codes: 0 written, 2 bad arguments, a bad scene or an unwritable file.
#include <cstdio>
#include <fstream>
#include <string>
#include <variant>

#include "portable/flat_world.h"
#include "scene/scene.h"

int main(int argc, char** argv) {
  constexpr int kExitBadInput = 2;
  constexpr const char* kUsage =
      "usage: physics-flatten SCENE.textproto [OUT.json]   the scene as a flat world (JSON)\n";
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (argc < 2 || argc > 3 || std::string(argv[1]).rfind('-', 0) == 0) {
    std::fputs(kUsage, stderr);
    return kExitBadInput;
  }
  scene::SceneResult loaded = scene::load_scene_file(argv[1]);
  if (const auto* error = std::get_if<scene::SceneError>(&loaded)) {
    std::fprintf(stderr, "%s\n", error->to_string().c_str());
    return kExitBadInput;
  }
  const scene::SceneDef& def = std::get<scene::SceneDef>(loaded);
  const std::string json =
      portable::to_json(portable::flatten({def.world, scene::fixed_dt(def), def.bodies}));
  if (argc == 2) {
    std::fputs(json.c_str(), stdout);
    return 0;
  }
  std::ofstream out(argv[2], std::ios::binary);
  out << json;
  out.close();
  if (!out) {
    std::fprintf(stderr, "physics-flatten: cannot write %s\n", argv[2]);
    return kExitBadInput;
  }
  return 0;
}
