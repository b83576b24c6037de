#pragma once
// What more than one phase of the sub-step uses in its inner loops: the constants
// of contact and support, and StepPhase, the base of each phase's file-local
// worker (the world, the scratch and the sub-step's constants, with the helpers
// several phases call). Defined here, inline: the phases call them per body and
// per pair, and the compiler inlines them into those loops.
#include <cstddef>
#include <cstdint>
#include <limits>

#include "physics/formulas.h"
#include "step_context.h"
#include "world_impl.h"

namespace phys {

inline constexpr std::uint32_t kNone = UINT32_MAX;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A contact whose normal is within 72.5 degrees of "up" (cosine 0.3) carries weight
// (supports). At 60 degrees, a circle sunk into a narrow gap between two resting
// neighbours, meeting them less than 30 degrees above level, was no load of theirs:
// the passes split its pushes half and half, pressing them apart into their
// pockets. The frictionless 16,000-circle pile then fell asleep only at 60 s, with
// rows of side-by-side circles compressed end to end (0.0148 m); at 72.5 degrees it
// sleeps at 43.5 s with 0.0042 m (docs/PHYSICS.md, "Stacks: shock propagation").
inline constexpr double kSupportCosine = 0.3;
// Candidate boxes grow by this fraction of a body's smaller half extent (the pushes
// of the position passes stay within the pairs found).
inline constexpr double kPushMargin = 0.1;
// How many bodies (or candidate pairs) ahead the loops over bodies scattered in
// memory prefetch.
inline constexpr std::uint32_t kPrefetchAhead = 8;

inline double component(const Vec2& v, int axis) { return axis == 0 ? v.x : v.y; }
inline double& component(Vec2& v, int axis) { return axis == 0 ? v.x : v.y; }

// Shock propagation, for both the position and the velocity passes: a body resting
// on support (a fixed body below it, or a supported body) is immovable for the
// bodies it carries, for contacts within 72.5 degrees of vertical. wa and wb are
// the inverse-mass weights of the pair; the carrier's becomes zero. On a plain
// array: a loop that passes it keeps it in a register, where a vector's pointer
// would be reloaded after every byte store (which may alias).
inline void carry(std::uint8_t* supported, bool shock, bool fixed, std::uint32_t lower_pos,
                  std::uint32_t upper_pos, double up, double& wa, double& wb) {
  if (fixed) {
    if (up < -kSupportCosine) supported[lower_pos] = 1;
  } else if (!shock) {
    return;
  } else if (up > kSupportCosine && supported[lower_pos]) {
    wa = 0.0;
    supported[upper_pos] = 1;
  } else if (up < -kSupportCosine && supported[upper_pos]) {
    wb = 0.0;
    supported[lower_pos] = 1;
  }
}

// The load factor of a contact's friction: for a support contact (within 72.5
// degrees of vertical), the load of the body on top; 1 for any other.
inline double load_on(bool fixed, const Body& lower, const Body& upper, double up) {
  if (up < -kSupportCosine) return lower.load;
  if (up > kSupportCosine && !fixed) return upper.load;
  return 1.0;
}

// Two bodies at rest on each other are left a slop apart by the push that
// separated them. If that pair were no contact in the next step, a column of
// bodies falling together would have no contact inside it every other step: the
// velocity pass would stop only its bottom, and the column would breathe by a
// millimetre and 0.1 m/s a step forever, never asleep. Pairs closer than this
// margin are resting contacts for the velocity pass, like touching ones (a gap
// within the slop is closed by no velocity), and touching for contact events.
// Circles get a wider margin on top (StepContext::speculative_margin).
inline double near_miss_margin(const WorldSettings& s) { return 2.0 * s.slop; }

// The base of each phase's worker: what every phase reads, and the helpers that
// need the world or the sub-step's constants.
class StepPhase {
 protected:
  StepPhase(const StepContext& ctx, WorldImpl& world)
      : w_(world), x_(world.scratch), c_(ctx), s_(ctx.settings) {}

  Body& body(std::uint32_t slot) { return w_.bodies[slot]; }
  const Body& body(std::uint32_t slot) const { return w_.bodies[slot]; }

  // The loops over the awake bodies in processing order read them where their
  // slots are: in a pile that has flowed, all over memory, where the hardware's
  // prefetcher cannot follow. Each asks for the body kPrefetchAhead places on.
  void prefetch_ahead(std::size_t p) const {
    if (p + kPrefetchAhead < w_.lists.active.size()) {
      __builtin_prefetch(&w_.bodies[w_.lists.active[p + kPrefetchAhead]]);
    }
  }

  // What drives a body: gravity and its own acceleration.
  Vec2 driving_acceleration(const Body& b) const {
    return c_.gravity_on ? b.acceleration + s_.gravity : b.acceleration;
  }

  // carry() on this sub-step's support marks.
  void carry(bool fixed, std::uint32_t lower_pos, std::uint32_t upper_pos, double up, double& wa,
             double& wb) {
    phys::carry(x_.supported.data(), c_.shock, fixed, lower_pos, upper_pos, up, wa, wb);
  }

  double near_miss_margin() const { return phys::near_miss_margin(s_); }

  // Marks candidate c as a contact with normal n; the velocity solver gathers
  // the marked candidates in candidate order (so no sort is needed).
  void record_contact(std::uint32_t c, Vec2 n) {
    x_.marks.contact_of[c] = 1;
    x_.marks.near_miss[c] = 0;
    x_.marks.normal[c] = n;
  }

  // How fast a hit must close on a sleeping body to wake it: a resting contact's
  // speed from above (resting_on_it), the sleep speed from the side or below.
  double wake_speed(bool resting_on_it) const {
    return resting_on_it ? c_.rest_speed : s_.sleep_speed;
  }

  WorldImpl& w_;
  StepScratch& x_;
  const StepContext c_;  // a copy: the loops read its constants here, not through a reference
  const WorldSettings& s_;
};

}  // namespace phys
