#pragma once
// The sub-step's scratch: arrays a phase fills and the same or a later phase of
// the same sub-step reads, kept in the world only so that they are not allocated
// again every sub-step. Nothing here carries meaning from one sub-step to the
// next (the world's state, which does, is in world_impl.h: the body lists, the
// candidate pairs, the warm-start pool). Arrays "per position" are indexed by a
// body's position in the processing order, "per candidate" by the candidate's
// index in WorldImpl::candidates.
#include <cstdint>
#include <utility>
#include <vector>

#include "contact_lanes.h"
#include "physics/broadphase.h"
#include "physics/vec2.h"
#include "step_records.h"

namespace phys {

struct StepScratch {
  // Not state, so a copied world (World::save, World::restore) copies none of it:
  // a copy starts empty, and assigning keeps the target's own buffers.
  StepScratch() = default;
  StepScratch(const StepScratch& /*other*/) {}
  StepScratch& operator=(const StepScratch& /*other*/) { return *this; }
  StepScratch(StepScratch&&) = default;
  StepScratch& operator=(StepScratch&&) = default;
  ~StepScratch() = default;

  // Written and read by order_by_height (step_order.cpp) alone.
  struct Order {
    std::vector<double> keys;                             // per position: height
    std::vector<std::pair<double, std::uint32_t>> keyed;  // merging joined bodies
    // Per position: the body's position before the sort, kept while the candidate
    // pairs are valid (so that they may be kept, renumbered).
    std::vector<std::uint32_t> from;
  } order;

  // Written by integrate (step_integrate.cpp); read by find_candidates, the moves
  // and (step_start) the position passes' static friction. Lives one sub-step.
  struct Motion {
    std::vector<Vec2> velocity;      // per position: velocity at the end of the free motion
    std::vector<Vec2> displacement;  // per position: free-motion displacement
    std::vector<Vec2> step_start;    // per position: position at the start (contact friction only)
    std::vector<Aabb> next_fat_boxes;  // per position: the boxes new pairs would be found with
  } motion;

  // Written and read by find_candidates (step_integrate.cpp) alone.
  struct Broadphase {
    UniformGrid active_grid;
    std::vector<BodyPair> active_pairs;
    std::vector<std::uint32_t> overlaps;
    // Renumbering kept pairs: per old position, the new one; the list regrouped.
    std::vector<std::uint32_t> position_now;
    std::vector<Candidate> regrouped;
  } broadphase;

  // The contacts and near misses found: reset by the recipe (step.cpp) before the
  // moves, marked by the moves' resting hits (step_moves.cpp) and by the position
  // passes (step_position.cpp), gathered by the velocity solver. Per candidate;
  // normal, near_miss and gap are meaningful only where contact_of is marked.
  struct Marks {
    std::vector<std::uint32_t> contact_of;  // kNone, or marked a contact
    std::vector<Vec2> normal;
    std::vector<std::uint8_t> near_miss;  // a near miss (speculative contact)
    std::vector<double> gap;              // a near miss's gap
  } marks;

  // Shock propagation's support marks, per position: cleared and rewritten by every
  // position pass and every velocity iteration, which alone read them.
  std::vector<std::uint8_t> supported;

  // Written and read by the position passes (step_position.cpp) alone.
  struct Position {
    std::vector<std::uint32_t> near_candidates;  // candidates worth another pass
    // A pair with a circle that touched (within the grown margin) in the first pass:
    // its normal, and `base`, its penetration then plus the normal's share of the
    // bodies' offset then, so that later passes find the penetration as
    // base - dot(normal, upper.position - lower.position).
    struct RelaxedPair {
      Vec2 normal;
      double base;
      std::uint32_t candidate;
      std::uint32_t corner;  // a circle beside a box's corner: no speculative margin
    };
    std::vector<RelaxedPair> relaxed;
    // Written by find_pinned_bodies (step_crush.cpp), read by the position passes
    // and the velocity solver: the positions of the bodies pinned against a static
    // body by a kinematic one, and per position the normal toward that static body
    // (zero for a body not pinned).
    std::vector<std::uint32_t> pinned;
    std::vector<Vec2> pin_normal;
  } position;

  // Written by the velocity solver (step_velocity.cpp); `contacts` is read after it
  // by sleep (step_sleep.cpp). Lives one sub-step (contacts is grow-only: the
  // solver says how many records are this sub-step's).
  struct Velocity {
    std::vector<ContactRecord> contacts;
    std::vector<ContactWeights> contact_weights;  // per contact: shock propagation's
    ContactLanes lanes;                           // the frictionless iterations' lanes
    std::vector<Vec2> solver_velocity;            // per position (and one zero after)
    std::vector<Vec2> before_contacts;            // per position, when support is held
    std::vector<std::uint8_t> in_contact;         // per position, when support is held
    // update_loads' (step_contact_memory.cpp), per position: what its supports
    // pushed up, and what rests on it pressed down.
    std::vector<double> support_impulse;
    std::vector<double> carried_impulse;
  } velocity;

  // The sleeping bodies hit hard enough to wake: added by the moves, the position
  // passes and the velocity solver, woken and cleared by update_sleep
  // (step_sleep.cpp) at the end of the sub-step.
  std::vector<std::uint32_t> to_wake;

  // Written and read by move_kinematic_bodies (step_kinematic.cpp) alone: the fixed
  // bodies a kinematic body's move passes.
  std::vector<std::uint32_t> kinematic_near;

  // Written and read by update_sleep (step_sleep.cpp) alone.
  struct Sleep {
    std::vector<std::uint8_t> still_ready;  // per position: still for sleep_time
    std::vector<std::uint32_t> island_parent;
    std::vector<std::uint8_t> island_ready;
    std::vector<std::uint8_t> goes_to_sleep;    // per position: this sub-step's verdict
    std::vector<std::uint32_t> first_support;   // per position: CSR offsets into supporters
    std::vector<std::uint32_t> supporters;      // positions of what each body rests on
    std::vector<std::uint32_t> support_cursor;  // filling supporters and held_list
    std::vector<std::uint8_t> held_state;       // sleep_held_groups: per position
    std::vector<std::pair<std::uint32_t, std::uint32_t>> holds;  // (held, holder) positions
    std::vector<std::uint32_t> held_start;  // per holder: CSR offsets into held_list
    std::vector<std::uint32_t> held_list;   // the bodies each holds
    std::vector<std::uint32_t> held_work;   // the walks' stack
  } sleep;
};

}  // namespace phys
