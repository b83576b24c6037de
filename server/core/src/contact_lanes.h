#pragma once
// The velocity iterations of a frictionless sub-step, two contacts at a time in
// SIMD lanes, with results identical to the one-at-a-time pass bit for bit.
//
// Why identical: an iteration visits the contacts in order, and each reads and
// writes only its own two bodies' velocities. Two contacts with no body in common
// may swap places without changing a bit; only contacts that share a body must
// keep their order. Each contact is given a level, one more than the last level
// of either of its bodies, and the contacts are visited level by level: a body's
// contacts still come in their order, and the contacts of one level share no body,
// so two of them fill two lanes. (Levels are a graph colouring that keeps each
// body's order; the bench's lattice rain of 16,000 circles has about 130 levels of
// 150 contacts while it flows.) Shock propagation's weights depend on the
// contacts' angles and order alone, not on velocities: the step finds them once,
// as it gathers the contacts, in the same order.
//
// Each lane does exactly the scalar pass's operations (no fused multiply-add: the
// build has -ffp-contract=off), so every velocity and impulse is the same double.
#include <cstdint>
#include <span>
#include <vector>

#include "physics/vec2.h"

namespace phys {

struct ContactRecord;

// Whether this build has the lanes (SSE2); without them the step keeps the scalar
// pass for every iteration.
#if defined(__SSE2__)
inline constexpr bool kHaveContactLanes = true;
#else
inline constexpr bool kHaveContactLanes = false;
#endif

// Shock propagation's weights for one contact: the inverse masses as the scalar
// pass uses them after `carry`.
struct ContactWeights {
  double lower;
  double upper;
};

class ContactLanes {
 public:
  // Packs the contacts (in the pass's order) with their weights and current
  // accumulated impulses. `bodies` is the number of velocities; the one after
  // them, velocity[bodies], must be zero: a fixed body's lane reads it.
  void pack(std::span<const ContactRecord> contacts, std::span<const ContactWeights> weights,
            std::uint32_t bodies);
  // One velocity iteration; true when some impulse changed by more than 1e-12
  // (the scalar pass's test for another iteration). The first iteration starts
  // each contact with a warm impulse from its record as the scalar pass does.
  bool iterate(Vec2* velocity, bool first_iteration);
  // The accumulated impulses back into the records.
  void unpack(std::span<ContactRecord> contacts) const;

  std::size_t levels() const { return level_count_; }

 private:
  // Two contacts, one per lane; a lane of an odd level's last pair is empty
  // (weights zero: it changes nothing).
  struct alignas(16) Pair {
    double nx[2];
    double ny[2];
    double w_lower[2];
    double w_upper[2];
    double mass[2];  // 1 / (w_lower + w_upper)
    double target[2];
    double impulse[2];
    std::uint64_t moves_upper[2];  // all ones when the upper body is awake (not fixed)
    std::uint32_t lower[2];
    std::uint32_t upper[2];  // the zero velocity after the bodies when fixed
  };

  template <bool kFirst>
  bool iterate(Vec2* velocity);

  std::vector<Pair> pairs_;
  std::vector<double> warm_;                    // per lane: the warm-start impulse
  std::vector<std::uint32_t> contact_of_lane_;  // per lane: the record, or none
  std::vector<std::uint32_t> last_level_;       // per body, while levelling
  std::vector<std::uint32_t> level_of_;         // per contact
  std::vector<std::uint32_t> next_lane_;        // per level, while packing
  std::size_t level_count_ = 0;
};

}  // namespace phys
