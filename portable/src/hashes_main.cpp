// physics-hashes: the state hashes the cross-platform checks compare, from the core
// and the scene library alone (no Protobuf, no Asio), so that it builds for every
// target: x86-64, AArch64 (scripts/test-aarch64.sh) and WebAssembly
// (scripts/test-wasm.sh). One line per world: "<name> <hash, 16 hex digits>".
//   physics-hashes [--steps N] FLAT.json...   each flat world (physics-flatten's output)
//                                             after N steps (default 600) of its dt
//   physics-hashes --library                  the golden worlds: the scene library's
//                                             scenes at the steps of their goldens, the
//                                             determinism scene, and det_math's results
// Exit codes: 0 done, 2 bad flags or a bad file.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "golden_worlds.h"
#include "portable/flat_world.h"

namespace {

constexpr int kExitBadInput = 2;
constexpr std::streamsize kMaxFileBytes = 64 << 20;

void print(const std::string& name, std::uint64_t hash) {
  std::printf("%s %016llx\n", name.c_str(), static_cast<unsigned long long>(hash));
}

std::string base_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The flat world in `path` after `steps` steps, or an error message.
std::variant<std::uint64_t, std::string> run_file(const std::string& path, long steps) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return path + ": cannot open";
  std::ostringstream text;
  text << file.rdbuf();
  if (text.str().size() > static_cast<std::size_t>(kMaxFileBytes))
    return path + ": larger than 64 MiB";
  auto values = portable::from_json(text.str());
  if (const auto* error = std::get_if<std::string>(&values)) return path + ": " + *error;
  auto flat = portable::unflatten(std::get<std::vector<double>>(values));
  if (const auto* error = std::get_if<std::string>(&flat)) return path + ": " + *error;
  const portable::FlatWorld& def = std::get<portable::FlatWorld>(flat);
  auto built = portable::build_world(def);
  if (const auto* error = std::get_if<std::string>(&built)) return path + ": " + *error;
  phys::World& world = std::get<phys::World>(built);
  for (long i = 0; i < steps; ++i) world.step(def.dt);
  return world.state_hash();
}

constexpr const char* kUsage =
    "usage: physics-hashes [--steps N] FLAT.json...   each flat world's state hash after N\n"
    "                                                 steps (default 600) of its dt\n"
    "       physics-hashes --library                  the golden worlds' state hashes\n";

int usage() {
  std::fputs(kUsage, stderr);
  return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (args.size() == 1 && args[0] == "--library") {
    for (const portable::GoldenWorld& golden : portable::golden_worlds())
      print(golden.name, golden.run());
    return 0;
  }
  long steps = 600;
  std::size_t first = 0;
  if (args.size() >= 2 && args[0] == "--steps") {
    char* end = nullptr;
    steps = std::strtol(args[1].c_str(), &end, 10);
    if (args[1].empty() || *end != '\0' || steps < 0 || steps > 1000000) return usage();
    first = 2;
  }
  if (first >= args.size()) return usage();
  for (std::size_t i = first; i < args.size(); ++i) {
    if (args[i].rfind('-', 0) == 0) return usage();  // a flag out of place
  }
  for (std::size_t i = first; i < args.size(); ++i) {
    const auto result = run_file(args[i], steps);
    if (const auto* error = std::get_if<std::string>(&result)) {
      std::fprintf(stderr, "physics-hashes: %s\n", error->c_str());
      return kExitBadInput;
    }
    print(base_name(args[i]), std::get<std::uint64_t>(result));
  }
  return 0;
}
