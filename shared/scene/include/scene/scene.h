#pragma once
// A scene as plain C++: what the server and physics-sim build a World from. The
// file format is proto/scene.proto in Protobuf text format; this header does not
// expose Protobuf, so the core and its users never see it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "physics/body.h"
#include "physics/fixed_timestep.h"
#include "physics/settings.h"
#include "physics/world.h"

namespace scene {

struct SceneDef {
  std::string name;
  phys::WorldSettings world;
  double tick_rate = 60.0;
  int steps_per_frame = 6;
  // Client inputs are clamped to this magnitude (m/s^2).
  double max_acceleration = 50.0;
  std::vector<phys::BodyDef> bodies;
  std::vector<phys::Vec2> spawn_points;
  // The body each client gets; its position is taken from a spawn point.
  phys::BodyDef player;
};

// Why a scene was refused: the file, the line (and column) where Protobuf gives
// one (0 when it does not), the field at fault, and what is wrong with it.
struct SceneError {
  std::string file;
  int line = 0;
  int column = 0;
  std::string field;
  std::string message;
  // "file:line:column: field: message", leaving out what is unknown.
  std::string to_string() const;
};

using SceneResult = std::variant<SceneDef, SceneError>;

// Limits that keep a hostile scene from using unbounded memory: the file is refused
// before it is read when larger, and the body count (grids included) is computed
// and refused before any body is made.
inline constexpr std::uintmax_t kMaxSceneFileBytes = 16u << 20;
inline constexpr std::int64_t kMaxSceneBodies = 1 << 20;
// Positions are refused beyond this distance from the origin on either axis: far
// out, a double still resolves about 2e-9 m, but nothing we test goes there.
inline constexpr double kMaxCoordinate = 1.0e7;
// Ticks per second, wherever a rate comes from and wherever it is stepped: the core's
// one range (physics/fixed_timestep.h).
using phys::kMaxTickRate;
using phys::kMinTickRate;
// False for NaN too.
constexpr bool is_valid_tick_rate(double rate) {
  return rate >= kMinTickRate && rate <= kMaxTickRate;
}
// "" for a valid rate, else "tick rate must be in [0.001, 1000] ticks per second,
// got R": every place that refuses a rate says it in these words.
std::string tick_rate_problem(double rate);
// Steps per frame are in [1, kMaxStepsPerFrame].
inline constexpr std::int64_t kMaxStepsPerFrame = 1000;

// Reads and checks a .textproto scene file.
SceneResult load_scene_file(const std::filesystem::path& path);
// Parses and checks scene text; `origin` names it in errors (a file name).
SceneResult parse_scene_text(std::string_view text, std::string_view origin);
// The scene built into the program (scenes/default.textproto, embedded at build time).
const SceneDef& default_scene();
std::string_view default_scene_text();

// A world holding the scene's bodies, in the scene's order (ids ascend with it).
// The scene must be one the loader accepted (or hold equally valid values): a body
// the core still refuses is a programmer error, reported by std::invalid_argument.
phys::World build_world(const SceneDef& scene);

// The fixed step of the scene: 1 / tick_rate.
double fixed_dt(const SceneDef& scene);

}  // namespace scene
