// physics-hashes: the state hashes the cross-platform checks compare, from the core
// and the scene library alone (no Protobuf, no Asio), so that it builds for every
// target: x86-64, AArch64 (scripts/test-aarch64.sh) and WebAssembly
// (scripts/test-wasm.sh). One line per world: "<name> <hash, 16 hex digits>".
//   physics-hashes [--steps N] [--time] FLAT.json...
//                                             each flat world (physics-flatten's output)
//                                             after N steps (default 600) of its dt;
//                                             --time adds the mean ms per step (wall)
//   physics-hashes --library                  the golden worlds: the scene library's
//                                             scenes at the steps of their goldens, the
//                                             determinism scene, and det_math's results
// Exit codes: 0 done, 2 bad flags or a bad file.
#include <chrono>
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

struct Run {
  std::uint64_t hash = 0;
  double ms_per_step = 0.0;
};

// The flat world in `path` after `steps` steps, or an error message.
std::variant<Run, std::string> run_file(const std::string& path, long steps) {
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
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) world.step(def.dt);
  const std::chrono::duration<double, std::milli> took = std::chrono::steady_clock::now() - start;
  return Run{world.state_hash(), steps > 0 ? took.count() / static_cast<double>(steps) : 0.0};
}

constexpr const char* kUsage =
    "usage: physics-hashes [--steps N] [--time] FLAT.json...\n"
    "                                                 each flat world's state hash after N\n"
    "                                                 steps (default 600) of its dt; --time\n"
    "                                                 adds the mean ms per step\n"
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
  bool timed = false;
  std::size_t first = 0;
  for (;;) {
    if (first + 1 < args.size() && args[first] == "--steps") {
      char* end = nullptr;
      steps = std::strtol(args[first + 1].c_str(), &end, 10);
      if (args[first + 1].empty() || *end != '\0' || steps < 0 || steps > 1000000) return usage();
      first += 2;
    } else if (first < args.size() && args[first] == "--time") {
      timed = true;
      first += 1;
    } else {
      break;
    }
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
    const Run& run = std::get<Run>(result);
    if (timed) {
      std::printf("%s %016llx %.4f\n", base_name(args[i]).c_str(),
                  static_cast<unsigned long long>(run.hash), run.ms_per_step);
    } else {
      print(base_name(args[i]), run.hash);
    }
  }
  return 0;
}
