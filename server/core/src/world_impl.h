#pragma once
// The world's private state. Bodies live in slots named by BodyId (index plus
// generation); the step works on dense lists of slot indices rebuilt when bodies
// are added, removed, fall asleep or wake.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "contact_tracker.h"
#include "physics/broadphase.h"
#include "physics/game_state.h"
#include "physics/world.h"
#include "query_index.h"
#include "sensor_tracker.h"
#include "step_records.h"
#include "step_scratch.h"

namespace phys {

// Last sub-step's contact impulses of a body toward the bodies above it in the
// processing order (warm start), kept apart from Body so the hot loops stay small.
// At most kWarmSlots per body. The awake bodies' entries sit in one pool, written
// in processing order by the velocity solver and read back in that order by the
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
  // Warm: the materials, read once per contact by the velocity solver (next to
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

  Aabb bounds() const { return box_around(position, half); }
  bool is_dynamic() const { return motion == Motion::Dynamic; }
};

// What decides which pairs collide, per slot: read when pairs are found (only in a
// world where some body is filtered or a sensor), never by the passes over contacts,
// so it lives apart from Body.
struct BodyFilter {
  Filter filter{};
  bool sensor = false;
  bool is_default() const { return !sensor && filter == Filter{}; }
};

// The dense lists of bodies the step walks, rebuilt (body_lists.cpp) when bodies
// are added, removed, fall asleep or wake. World state: they live across steps.
struct BodyLists {
  std::vector<std::uint32_t> active;  // awake dynamic bodies, in processing order
  // How many bodies at the end of `active` joined it at the last rebuild (woken or
  // added, in slot order) and are still to be merged into the order by height; 0
  // when the whole list is new (its order then is slot order).
  std::size_t joined = 0;
  std::vector<std::uint32_t> fixed;  // static and sleeping bodies, ascending index
  std::vector<Aabb> fixed_boxes;
  UniformGrid fixed_grid;
  std::size_t fixed_circles = 0;   // circles among the static and sleeping bodies
  std::size_t fixed_sleeping = 0;  // sleeping bodies among them
  // Positions in `fixed` of the kinematic bodies (filled only when there are any):
  // each sub-step moves them and their boxes (step_kinematic.cpp).
  std::vector<std::uint32_t> kinematic;
};

// The candidate pairs of the awake bodies, grouped by the lower body's position
// in the processing order. World state: a sub-step in which every body stays
// inside the fat box its pairs were found with keeps them (find_candidates).
struct CandidatePairs {
  std::vector<Candidate> list;
  std::vector<std::uint32_t> first;  // per position: CSR offsets into list
  std::vector<Aabb> fat_boxes;       // per position: the boxes they were found with
  bool valid = false;                // false after the lists changed
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
  // Heap bytes of the state a SavedWorld copies (its arrays' capacity).
  std::size_t state_bytes() const;
  std::size_t alive_count() const { return alive_count_; }
  std::size_t dynamic_count() const { return dynamic_count_; }
  std::size_t kinematic_count() const { return kinematic_count_; }
  // Whether any body is filtered or a sensor: only then are pairs tested against
  // the filters when they are found.
  bool filtering() const { return filtered_count_ != 0; }
  // Whether two bodies may collide: neither a sensor, and their filters agree.
  bool pair_collides(std::uint32_t a, std::uint32_t b) const {
    const BodyFilter& fa = filters[a];
    const BodyFilter& fb = filters[b];
    return !fa.sensor && !fb.sensor && should_collide(fa.filter, fb.filter);
  }
  // pair_collides, or true in a world without filters and sensors.
  bool pair_collides_or_unfiltered(std::uint32_t a, std::uint32_t b) const {
    return !filtering() || pair_collides(a, b);
  }
  // Wakes the sleeping bodies whose boxes meet `around`, but `except`.
  void wake_in(const Aabb& around, std::uint32_t except);
  // A body's filter changed: the pairs are found anew.
  void set_filter(std::uint32_t slot, const Filter& filter);
  // The lowest slot of an alive body with this name, or kNoSlot.
  static constexpr std::uint32_t kNoSlot = UINT32_MAX;
  std::uint32_t find_name(std::string_view name) const;

  // The body lists as the step needs them: rebuilt first if bodies fell asleep,
  // woke, or were added, removed or moved by hand.
  const BodyLists& current_lists() {
    if (lists_dirty_) rebuild_lists();
    return lists;
  }
  // A body update_sleep put to sleep: the lists change at the next rebuild.
  void fell_asleep(std::uint32_t slot) {
    changed_slots_.push_back(slot);
    lists_dirty_ = true;
    query_index.forget_sleeping();
    query_index.forget_moving();
  }
  // The lists as they stand, if no change since their last rebuild left them stale.
  const BodyLists* lists_if_current() const { return lists_dirty_ ? nullptr : &lists; }

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
  BodyLists lists;
  CandidatePairs candidates;
  StepScratch scratch;
  // Cold, per slot: filters and sensors (read when pairs are found), names.
  std::vector<BodyFilter> filters;
  std::vector<std::string> names;
  // (name, slot) of every alive named body, sorted: find_body's index.
  std::vector<std::pair<std::string, std::uint32_t>> name_index;
  // The sensors' slots, ascending; their overlaps and events.
  std::vector<std::uint32_t> sensors;
  SensorTracker sensor_tracker;
  // Crushes (World::crush_events), tagged with the step that found them: a list
  // whose step is not the last step's is stale, and the next crush clears it.
  std::vector<CrushEvent> crushes;
  void record_crush(std::uint32_t kinematic, std::uint32_t dynamic, std::uint32_t fixed);
  // The bodies filed for World's queries; not state: forgotten (forget) whenever
  // bodies move, come or go, and empty in a copy.
  mutable QueryIndex query_index;
  // The game's variables and timers (World::game_state): copied, written and hashed
  // with the bodies.
  GameState game_state;

 private:
  friend class World;
  template <class A>
  friend void state_fields(A& a, WorldImpl& w);  // world_bytes.cpp
  friend std::string check_read_state(const WorldImpl& w);

  BodyDefError check(const BodyDef& def) const;
  // body_lists.cpp: the lists above, after bodies fell asleep, woke, or were
  // added, removed or moved by hand.
  void rebuild_lists();
  void rebuild_fixed_and_joined();
  void update_fixed_and_joined();

  std::vector<std::uint32_t> free_slots_;  // LIFO: deterministic reuse
  std::size_t alive_count_ = 0;
  std::size_t dynamic_count_ = 0;  // bodies never change their motion once made
  std::size_t kinematic_count_ = 0;
  std::size_t filtered_count_ = 0;  // alive bodies whose BodyFilter is not the default

  bool lists_dirty_ = true;
  // Whether the rebuild must walk every body (a body was added, removed or moved by
  // hand); otherwise only the bodies that fell asleep or woke since, in
  // changed_slots_, can have changed lists (a settling pile: some every step).
  bool rebuild_all_ = true;
  std::vector<std::uint32_t> changed_slots_;
  // rebuild_lists' scratch.
  std::vector<std::uint32_t> previous_active_;
  std::vector<std::uint8_t> listed_;  // per slot: kept in active (all 0 between uses)
  std::vector<std::uint32_t> merged_fixed_;
  std::vector<Aabb> merged_fixed_boxes_;
};

}  // namespace phys
