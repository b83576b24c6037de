#pragma once
// Scenes built in code for the integration tests, each shaped for what one test
// must see clearly.
#include <cstddef>

#include "scene/scene.h"

namespace itest {

// No bodies but the players, far apart in open space: a player's body follows the
// closed-form kinematics exactly, and nothing else can touch it.
scene::SceneDef free_flight_scene(bool with_gravity);

// `count` dynamic circles at rest in a grid, no gravity: large snapshots (about 40
// bytes a body) for filling a slow reader's socket, cheap steps.
scene::SceneDef crowd_scene(std::size_t count);

}  // namespace itest
