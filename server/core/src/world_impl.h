#pragma once
// The world's private state. Bodies live in slots named by BodyId (index plus
// generation); the step works on dense lists of slot indices rebuilt when bodies
// are added, removed, fall asleep or wake.
#include <cstdint>
#include <utility>
#include <vector>

#include "contact_lanes.h"
#include "contact_tracker.h"
#include "physics/broadphase.h"
#include "physics/world.h"

namespace phys {

// Last sub-step's contact impulses of a body toward the bodies above it in the
// processing order (warm start), kept apart from Body so the hot loops stay small.
// At most kWarmSlots per body. The awake bodies' entries sit in one pool, written
// in processing order by the restitution phase and read back in that order by the
// next one; a body that leaves the awake list keeps its entries in its own slot
// (WarmImpulses) until it is awake again.
struct WarmEntry {
  std::uint32_t partner;
  std::uint32_t generation;
  double impulse;
  double tangent_impulse;
};
constexpr std::uint8_t kWarmSlots = 8;
constexpr std::uint32_t kWarmInSlot = UINT32_MAX;  // warm_first: entries in WarmImpulses
struct WarmImpulses {
  WarmEntry entries[kWarmSlots]{};
};

// Aligned to a cache line, so that the hot fields below are one line and the warm
// ones the next: unaligned, a body's first 64 bytes straddled two lines, and every
// contact touched three of a body's lines instead of two (a few per cent of a step
// in a flowing pile of 16,000 circles).
struct alignas(64) Body {
  // Hot: read by every pass over the contacts (the first cache line, and the
  // second up to the generation).
  Vec2 position{};
  Vec2 half{};  // half extents of the bounding box (a circle's: radius, radius)
  Vec2 velocity{};
  double radius = 0.0;    // circles
  double inv_mass = 0.0;  // 0: static, or immovable
  Vec2 correction{};      // how far penetration resolution moved it this sub-step
  Shape shape = Shape::Box;
  Motion motion = Motion::Dynamic;
  bool alive = false;
  bool awake = true;
  std::uint32_t generation = 0;
  // Warm: the materials, read once per contact by the restitution phase (next to
  // the hot fields, so that a contact does not touch a body's cold line).
  double restitution = 0.0;
  double contact_friction = 0.0;
  // How many times its own weight its supports carried in the last sub-step (1 for
  // a body carrying nothing): the weight of what rests on it, which shock
  // propagation keeps out of its contact impulses, put back into its friction.
  // Read with the materials, by every contact with friction.
  double load = 1.0;
  // Its own acceleration: read by integration, and by the position passes' static
  // friction (which never moves a body further the way it is driven), so it ends
  // the second cache line with the materials.
  Vec2 acceleration{};
  // Cold: read once a step or less.
  double mass = 0.0;
  Vec2 friction{};
  double still_time = 0.0;  // seconds it has stayed near still_anchor
  // How much of its acceleration (gravity and its own) its contacts held back in
  // the last sub-step, per axis (m/s^2), applied as a force in the next one so that
  // a resting body does not sink into its supports and get pushed back out every
  // step, nor creep along them when friction holds a push.
  Vec2 held{};
  Vec2 still_anchor{};

  Aabb bounds() const { return {position - half, position + half}; }
  bool is_dynamic() const { return motion == Motion::Dynamic; }
};

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

// A pair found touching or overlapping, with everything the restitution phase's
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
  std::uint32_t upper_generation;
  bool fixed;  // upper is a static or sleeping body
};

class WorldImpl {
 public:
  explicit WorldImpl(const WorldSettings& settings);

  BodyId add_body(const BodyDef& def, BodyDefError* error);
  bool remove_body(BodyId id);
  Body* find(BodyId id);
  const Body* find(BodyId id) const;
  BodyState state_of(std::uint32_t index) const;
  void wake(std::uint32_t index);
  void step(double dt);
  std::uint64_t state_hash() const;

  WorldSettings settings;
  StageCounters counters;
  StepProfile profile;
  std::uint64_t steps = 0;
  std::vector<Body> bodies;
  // Contact events (World::set_contact_events): off, nothing notes a touch.
  bool contact_events_on = false;
  ContactTracker contact_tracker;
  // Warm-start impulses, per slot: how many, and where (warm_pool from warm_first,
  // or warm[slot] when warm_first is kWarmInSlot).
  std::vector<std::uint8_t> warm_count;
  std::vector<std::uint32_t> warm_first;
  std::vector<WarmImpulses> warm;
  std::vector<WarmEntry> warm_pool;
  // The entry of the pair (slot, partner), or null.
  const WarmEntry* warm_entry(std::uint32_t slot, std::uint32_t partner,
                              std::uint32_t partner_generation) const {
    const WarmEntry* entries =
        warm_first[slot] == kWarmInSlot ? warm[slot].entries : warm_pool.data() + warm_first[slot];
    for (std::uint8_t i = 0; i < warm_count[slot]; ++i) {
      if (entries[i].partner == partner && entries[i].generation == partner_generation) {
        return &entries[i];
      }
    }
    return nullptr;
  }

 private:
  friend class StepRunner;
  friend class World;

  BodyDefError check(const BodyDef& def) const;
  // body_lists.cpp: the dense lists below, after bodies fell asleep, woke, or were
  // added, removed or moved by hand.
  void rebuild_lists();
  void rebuild_fixed_and_joined();
  void update_fixed_and_joined();
  void fell_asleep(std::uint32_t slot) {
    changed_slots_.push_back(slot);
    lists_dirty_ = true;
  }

  std::vector<std::uint32_t> free_slots_;  // LIFO: deterministic reuse
  std::size_t alive_count_ = 0;
  std::size_t dynamic_count_ = 0;

  // Dense lists, rebuilt when `lists_dirty_`.
  bool lists_dirty_ = true;
  // Whether the rebuild must walk every body (a body was added, removed or moved by
  // hand); otherwise only the bodies that fell asleep or woke since, in
  // changed_slots_, can have changed lists (a settling pile: some every step).
  bool rebuild_all_ = true;
  std::vector<std::uint32_t> changed_slots_;
  std::vector<std::uint32_t> active_;  // awake dynamic bodies, in processing order
  // How many bodies at the end of active_ joined it at the last rebuild (woken or
  // added, in slot order) and are still to be merged into the order by height; 0
  // when the whole list is new (its order then is slot order).
  std::size_t joined_ = 0;
  std::vector<std::uint32_t> previous_active_;  // rebuild_lists' scratch
  std::vector<std::uint8_t> listed_;  // per slot: kept in active_ (scratch, all 0 between uses)
  std::vector<std::uint32_t> fixed_;  // static and sleeping bodies, ascending index
  UniformGrid fixed_grid_;
  UniformGrid active_grid_;
  std::vector<Aabb> fixed_boxes_;
  std::vector<std::uint32_t> merged_fixed_;  // update_fixed_and_joined's scratch
  std::vector<Aabb> merged_fixed_boxes_;
  std::size_t fixed_circles_ = 0;   // circles among the static and sleeping bodies
  std::size_t fixed_sleeping_ = 0;  // sleeping bodies among them

  // Per-step scratch, kept to avoid allocating every step.
  std::vector<Aabb> fat_boxes_;       // the boxes the current candidates were found with
  std::vector<Aabb> next_fat_boxes_;  // this sub-step's, should they be found again
  bool candidates_valid_ = false;
  std::vector<BodyPair> active_pairs_;
  std::vector<std::uint32_t> overlaps_;
  std::vector<Candidate> candidates_;
  std::vector<std::uint32_t> first_candidate_;       // per active position: CSR offsets
  std::vector<ContactRecord> contacts_;              // grow-only; the step counts those in use
  std::vector<ContactWeights> contact_weights_;      // shock propagation's, per contact
  ContactLanes contact_lanes_;                       // the frictionless iterations' lanes
  std::vector<std::uint32_t> contact_of_candidate_;  // kNone, or marked a contact
  std::vector<Vec2> contact_normal_;                 // per candidate, when marked
  std::vector<std::uint8_t> supported_;              // per position in the processing order
  std::vector<Vec2> step_velocity_;                  // velocity at the end of the free motion
  std::vector<Vec2> solver_velocity_;            // the restitution phase's velocities, by position
  std::vector<Vec2> step_displacement_;          // free-motion displacement this sub-step
  std::vector<std::uint8_t> contact_near_miss_;  // per candidate, when marked: a near miss
  std::vector<double> contact_gap_;              // per candidate, when a near miss: its gap
  std::vector<Vec2> velocity_before_contacts_;   // per position, when support is held
  std::vector<std::uint8_t> in_contact_;         // per position
  std::vector<double> support_impulse_;          // per position: what its supports pushed up
  std::vector<double> carried_impulse_;          // per position: what rests on it pressed down
  std::vector<Vec2> step_start_;                 // position at the start of the sub-step (friction)
  std::vector<std::uint32_t> to_wake_;
  std::vector<std::uint32_t> near_candidates_;  // candidates worth another position pass
  std::vector<double> sort_keys_;
  std::vector<std::pair<double, std::uint32_t>> keyed_order_;  // merging joined bodies
  std::vector<std::uint8_t> sleep_ready_;
  std::vector<std::uint8_t> still_ready_;  // per position: still for sleep_time
  std::vector<std::uint32_t> island_parent_;
  std::vector<std::uint8_t> goes_to_sleep_;    // per position, this sub-step's verdict
  std::vector<std::uint32_t> first_support_;   // per position: CSR offsets into supporters_
  std::vector<std::uint32_t> supporters_;      // positions of what each body rests on
  std::vector<std::uint32_t> support_cursor_;  // filling supporters_
  std::vector<std::uint8_t> held_state_;       // sleep_held_groups: per position
  std::vector<std::pair<std::uint32_t, std::uint32_t>> holds_;  // (held, holder) positions
  std::vector<std::uint32_t> held_start_;  // per holder: CSR offsets into held_list_
  std::vector<std::uint32_t> held_list_;   // the bodies each holds
  std::vector<std::uint32_t> held_work_;   // the walks' stack
};

}  // namespace phys
