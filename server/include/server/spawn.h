#pragma once
// Where a joining client's body goes: the first place, in a fixed order, where the
// scene's player body overlaps no body of the world. The order is every spawn point
// in the scene's order, then rings of positions around them, so the choice depends
// only on the scene and the world's state (deterministic under lockstep).
#include <cstdint>
#include <optional>

#include "physics/body.h"
#include "physics/world.h"
#include "scene/scene.h"

namespace server {

// How many rings of positions around each spawn point are tried after the points
// themselves; ring r lies r * 2.5 player sizes away.
inline constexpr int kSpawnRings = 4;

// `seat`, when given, puts spawn point (seat mod the number of spawn points) first:
// a seated player's place depends on its seat, not on who joined before it.
std::optional<phys::Vec2> find_spawn_position(const scene::SceneDef& scene,
                                              const phys::World& world,
                                              std::optional<std::uint32_t> seat = std::nullopt);

}  // namespace server
