#pragma once
// Bodies that start inside one another are refused: the first step would push them
// apart at once, so a scene that overlaps is almost always a typo (a position, a
// grid's spacing smaller than its bodies) and would start with a jolt.
#include <cstddef>
#include <vector>

#include "field_checker.h"
#include "field_path.h"
#include "scene/scene.h"

namespace scene::detail {

// Where a run of SceneDef::bodies came from: `bodies[i]` (one body each, from
// `first`) or one grid (`grids[g]`, every body from `first` to the next source).
struct BodySource {
  std::size_t first = 0;
  FieldPath path;
  bool grid = false;
};

// Two bodies overlap when they interpenetrate by more than kOverlapTolerance on
// every axis the shapes meet in (touching is allowed: stacks and grids are laid out
// edge to edge). Pairs that never collide are allowed: two static bodies (level
// geometry may be built of overlapping pieces that never move), static and
// kinematic ones among themselves, a sensor with anything, and pairs their filters
// keep apart. The first overlap in body order fails.
inline constexpr double kOverlapTolerance = 1.0e-6;
bool check_overlaps(Checker& check, const SceneDef& def, const std::vector<BodySource>& sources);

}  // namespace scene::detail
