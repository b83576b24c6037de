#pragma once
// A grid of the scene -> the bodies it places: its template checked once, its
// counts bounded before anything is made, every placed body checked against the
// coordinate limit and the world's bounds.
#include "field_checker.h"
#include "scene.pb.h"
#include "scene/scene.h"

namespace scene::detail {

// Appends the grid's bodies to def->bodies, within the scene's body limit.
bool check_grid(Checker& check, const physics::scene::Grid& grid, const FieldPath& path,
                SceneDef* def);

}  // namespace scene::detail
