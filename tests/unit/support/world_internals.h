#pragma once
// The step's state behind a World, for the core's white-box tests: the candidate
// pairs and the body lists the last sub-step worked with.
#include "physics/world.h"
#include "world_impl.h"

namespace phys {

struct WorldInternals {
  static const WorldImpl& of(const World& world) { return *world.impl_; }
};

}  // namespace phys
