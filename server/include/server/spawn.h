#pragma once
// Where a joining client's body goes: the first place, in a fixed order, where the
// scene's player body overlaps no body of the world. The order is every spawn point
// in the scene's order, then rings of positions around them, so the choice depends
// only on the scene and the world's state (deterministic under lockstep).
#include <optional>

#include "physics/body.h"
#include "physics/world.h"
#include "scene/scene.h"

namespace server {

// How many rings of positions around each spawn point are tried after the points
// themselves; ring r lies r * 2.5 player sizes away.
inline constexpr int kSpawnRings = 4;

std::optional<phys::Vec2> find_spawn_position(const scene::SceneDef& scene,
                                              const phys::World& world);

// The axis-aligned box a body occupies.
phys::Aabb bounds_of(const phys::BodyState& body);
phys::Aabb bounds_of(const phys::BodyDef& body, phys::Vec2 at);

}  // namespace server
