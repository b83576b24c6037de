#pragma once
// A world's settings and bodies as a flat list of doubles: what a build without
// Protobuf (AArch64 and WebAssembly cross builds, a browser) loads a scene from.
// physics-flatten writes it from a scene file, as a JSON array of numbers printed
// to 17 significant digits, which every correctly rounding reader (strtod,
// JSON.parse) turns back into the same doubles. docs/SCENES.md describes it.
//
// Layout, version 1:
//   [0]        1 (the version)
//   [1..25]    WorldSettings: gravity x, y; integrator (0 explicit Euler, 1
//              semi-implicit Euler, 2 exact); substeps; slop; position iterations;
//              velocity iterations; warm starting (0/1); continuous (0/1); shock
//              propagation (0/1); hold resting support (0/1); rest speed; max speed;
//              max acceleration; sleeping (0/1); sleep speed; sleep time; has bounds
//              (0/1); bounds min x, min y, max x, max y; max body size; max bodies;
//              SIMD contact lanes (0/1)
//   [26]       dt, the scene's fixed step (1 / tick rate)
//   [27]       N, the body count
//   then N bodies of 16: shape (0 circle, 1 box); motion (0 static, 1 dynamic);
//              position x, y; velocity x, y; acceleration x, y; radius; half
//              extents x, y; mass; restitution; friction x, y; contact friction
// Version 2, written only when a body is kinematic, filtered or a sensor (so that
// every other world stays version 1): the same, but [0] is 2, motion may be 2
// (kinematic), and each body has 4 values more (20): category bits, mask bits,
// group (whole numbers in the ranges of phys::Filter's fields); sensor (0/1).
// Names are not carried: they are not in the state hash.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "physics/body.h"
#include "physics/settings.h"
#include "physics/world.h"

namespace portable {

inline constexpr double kFlatVersion = 1.0;
inline constexpr double kFlatVersionWithFilters = 2.0;
inline constexpr std::size_t kFlatHeader = 28;
inline constexpr std::size_t kFlatBodyFields = 16;
inline constexpr std::size_t kFlatBodyFieldsWithFilters = 20;

struct FlatWorld {
  phys::WorldSettings settings;
  double dt = 1.0 / 60.0;
  std::vector<phys::BodyDef> bodies;
};

std::vector<double> flatten(const FlatWorld& world);

// The world the numbers describe, or why they do not describe one (wrong version or
// length, a field that must be a whole number or a flag and is not, settings
// the core refuses): never a crash, and nothing allocated beyond the input's
// own size.
std::variant<FlatWorld, std::string> unflatten(std::span<const double> values);

// The JSON array of numbers, and back ("[1, 0, -9.81, ...]"); reading refuses
// anything else with a message that says where.
std::string to_json(std::span<const double> values);
std::variant<std::vector<double>, std::string> from_json(std::string_view text);

// A World holding the bodies in order (ids ascend with it), or which body the core
// refused and why. Throws nothing: the WebAssembly build has no exceptions.
std::variant<phys::World, std::string> build_world(const FlatWorld& world);

}  // namespace portable
