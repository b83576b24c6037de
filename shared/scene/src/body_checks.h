#pragma once
// One body of the scene (or the template a grid or the player repeats) -> a core
// BodyDef: its name, shape, placement, motion and material checked; and whether a
// placed body lies inside the world's bounds.
#include <string_view>

#include "field_checker.h"
#include "physics/body.h"
#include "physics/settings.h"
#include "scene.pb.h"

namespace scene::detail {

// Checks one body (or a grid's or the player's template, whose position must be
// left unset) and converts it.
bool check_body(Checker& check, const physics::scene::Body& body, const FieldPath& path,
                const phys::WorldSettings& settings, bool is_template, phys::BodyDef* out);

// Whether the body's bounding box lies inside the world's bounds (edges included).
bool inside_bounds(const phys::WorldSettings& settings, const phys::BodyDef& body);

// A fault at `path` unless `body` lies inside the bounds; `what` names it.
bool check_inside(Checker& check, const FieldPath& path, const phys::WorldSettings& settings,
                  const phys::BodyDef& body, std::string_view what);

}  // namespace scene::detail
