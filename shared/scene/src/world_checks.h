#pragma once
// The scene's world block -> the core's WorldSettings and the server's tick
// settings, each number checked against its range and then against the core's own
// verdict (phys::check_settings).
#include "field_checker.h"
#include "scene.pb.h"
#include "scene/scene.h"

namespace scene::detail {

// Fills def->world, def->tick_rate, def->steps_per_frame and def->max_acceleration
// from what `world` sets; what it leaves unset keeps its default.
bool check_world(Checker& check, const physics::scene::World& world, SceneDef* def);

}  // namespace scene::detail
