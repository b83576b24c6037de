#pragma once
// The determinism scene: a room with a floor and two walls, a staircase of static
// boxes, a static circle and 40 dynamic bodies of both shapes, mixed masses,
// restitutions and frictions, launched in different directions; body 0 is pushed
// left and right every 50 steps, and at step 500 one body is removed and another
// added, so that id reuse is part of what must repeat. The golden state hash after
// 1000 steps at 60 Hz with the default WorldSettings is in
// tests/unit/determinism_test.cpp; physics-hashes runs the same scene on every
// platform CI checks.
#include <vector>

#include "physics/world.h"

namespace scenes {

inline constexpr int kDeterminismSteps = 1000;

// Adds the bodies to `world` and returns the dynamic ones' ids, in order.
std::vector<phys::BodyId> add_determinism_scene(phys::World& world);

// The input script, applied before step `step` (0-based).
void apply_determinism_inputs(phys::World& world, const std::vector<phys::BodyId>& dynamic,
                              int step);

}  // namespace scenes
