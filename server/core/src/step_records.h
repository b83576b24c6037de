#pragma once
// The pair records the step's phases hand on: candidate pairs (found by
// find_candidates, kept across steps while they hold) and contact records (the
// velocity solver's, read by sleep after it).
#include <cstdint>

#include "physics/vec2.h"

namespace phys {

// One candidate pair whose fattened boxes overlap this sub-step. `lower` is an
// awake body; `upper` another awake body later in the processing order, or (when
// `fixed`) a static or sleeping body.
struct Candidate {
  std::uint32_t lower;      // slot
  std::uint32_t upper;      // slot
  std::uint32_t lower_pos;  // position of `lower` in the processing order
  std::uint32_t upper_pos;  // position of `upper` there (unused when `fixed`)
  bool fixed;
};

// A pair found touching or overlapping, with everything the velocity solver's
// iterations read about it, so that they walk one array and the two bodies only.
struct ContactRecord {
  std::uint32_t lower;      // slot
  std::uint32_t upper;      // slot
  std::uint32_t lower_pos;  // positions in the processing order (upper_pos unused when fixed)
  std::uint32_t upper_pos;
  Vec2 normal;  // from lower toward upper
  double up;    // dot(normal, up): the support test of shock propagation
  double inv_mass_lower;
  double inv_mass_upper;   // 0 when fixed
  double target;           // the closing velocity the contact should end with
  double warm;             // last sub-step's impulse on this pair (warm start)
  double warm_tangent;     // and its friction impulse
  double mu;               // contact friction, mixed
  double impulse;          // accumulated normal impulse
  double tangent_impulse;  // accumulated friction impulse
  // A kinematic upper body's velocity along the tangent (-normal.y, normal.x); 0 for
  // any other; written and read only in a world with kinematic bodies. (Its velocity
  // along the normal is taken out of `target`.)
  double upper_slide;
  std::uint32_t upper_generation;
  bool fixed;  // upper is a static or sleeping body
};

}  // namespace phys
