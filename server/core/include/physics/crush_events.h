#pragma once
// Crush events: a dynamic body pinned between a moving kinematic body and a static
// one. A kinematic body is moved by its velocity alone and a static body never
// moves, so when the gap between them is narrower than the dynamic body, one of the
// three must give: the dynamic body. The static body wins (it is kept on the static
// body's near side), and the kinematic body goes on through it, overlapping it.
// The step reports each such triple so that game rules can kill or respawn the
// crushed body (World::crush_events).
//
// Pinned. Before each collide phase of a sub-step, an awake dynamic body touching a
// kinematic body is pinned when a static body touches or overlaps it on the opposite
// side (their normals from the dynamic body point away from each other) and the two
// are closer than the body is wide (its overlaps with them add up to more than the
// slop). A pinned body is kept awake. A crush is reported for a step when the body
// was pinned in any of its sub-steps. Only a body touching both is pinned, not a row
// of bodies between them. (docs/PHYSICS.md, "Kinematic bodies".)
#include <cstdint>

#include "physics/body.h"

namespace phys {

struct CrushEvent {
  // World::step_count() after the step that produced it (the first step is 1).
  std::uint64_t step = 0;
  BodyId kinematic;
  BodyId dynamic;
  BodyId fixed;  // the static body

  bool operator==(const CrushEvent&) const = default;
};

}  // namespace phys
