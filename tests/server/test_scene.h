#pragma once
// Small scenes for the server's tests, built in code so each test states its world.
#include "scene/scene.h"

namespace server_test {

// No gravity, no friction, no static bodies: a client's ball moves exactly as the
// kinematics say. Spawn points at (0, 0), (10, 0), (20, 0); player: circle r = 0.5.
scene::SceneDef free_space_scene();

// free_space_scene plus one dynamic box that belongs to nobody, at (-10, 0).
scene::SceneDef scene_with_unowned_box();

}  // namespace server_test
