#pragma once
// The world's private state. Bodies live in slots named by BodyId (index plus
// generation); the step works on dense lists of slot indices rebuilt when bodies
// are added, removed, fall asleep or wake.
#include <cstdint>
#include <vector>

#include "physics/broadphase.h"
#include "physics/world.h"

namespace phys {

struct Body {
  Vec2 position{};
  Vec2 velocity{};
  Vec2 acceleration{};
  Vec2 half{};          // half extents of the bounding box (a circle's: radius, radius)
  double radius = 0.0;  // circles
  double mass = 0.0;
  double inv_mass = 0.0;  // 0: static, or immovable
  double restitution = 0.0;
  Vec2 friction{};
  double still_time = 0.0;  // seconds it has stayed near still_anchor
  Vec2 still_anchor{};
  Vec2 correction{};  // how far penetration resolution moved it this sub-step
  // Last sub-step's contact impulses toward the bodies it supported (warm start).
  struct WarmImpulse {
    std::uint32_t partner;
    std::uint32_t generation;
    double impulse;
  };
  static constexpr std::uint8_t kWarmSlots = 8;
  WarmImpulse warm[kWarmSlots]{};
  std::uint8_t warm_count = 0;
  double warm_impulse(std::uint32_t partner, std::uint32_t partner_generation) const {
    for (std::uint8_t i = 0; i < warm_count; ++i) {
      if (warm[i].partner == partner && warm[i].generation == partner_generation) {
        return warm[i].impulse;
      }
    }
    return 0.0;
  }
  std::uint32_t generation = 0;
  Shape shape = Shape::Box;
  Motion motion = Motion::Dynamic;
  bool alive = false;
  bool awake = true;

  Aabb bounds() const { return {position - half, position + half}; }
  bool is_dynamic() const { return motion == Motion::Dynamic; }
};

// One candidate pair whose fattened boxes overlap this sub-step. `lower` is an
// awake body; `upper` another awake body later in the processing order, or (when
// `fixed`) a static or sleeping body.
struct Candidate {
  std::uint32_t lower;
  std::uint32_t upper;
  bool fixed;
};

// A pair found touching or overlapping, kept for the restitution phase.
struct ContactRecord {
  std::uint32_t candidate;
  Vec2 normal;   // from lower toward upper
  bool support;  // the normal is within 60 degrees of "up" (against gravity)
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

 private:
  friend class StepRunner;
  friend class World;

  BodyDefError check(const BodyDef& def) const;
  void rebuild_lists();

  std::vector<std::uint32_t> free_slots_;  // LIFO: deterministic reuse
  std::size_t alive_count_ = 0;
  std::size_t dynamic_count_ = 0;

  // Dense lists, rebuilt when `lists_dirty_`.
  bool lists_dirty_ = true;
  std::vector<std::uint32_t> active_;  // awake dynamic bodies, in processing order
  std::vector<std::uint32_t> fixed_;   // static and sleeping bodies, ascending index
  UniformGrid fixed_grid_;
  UniformGrid active_grid_;
  std::vector<Aabb> fixed_boxes_;

  // Per-step scratch, kept to avoid allocating every step.
  std::vector<Aabb> active_boxes_;
  std::vector<BodyPair> active_pairs_;
  std::vector<std::uint32_t> overlaps_;
  std::vector<Candidate> candidates_;
  std::vector<std::uint32_t> first_candidate_;     // per active position: CSR offsets
  std::vector<std::uint32_t> position_in_active_;  // slot -> position in active_
  std::vector<ContactRecord> contacts_;
  std::vector<std::uint32_t> contact_of_candidate_;
  std::vector<std::uint8_t> supported_;
  std::vector<Vec2> step_velocity_;      // velocity at the end of the free motion
  std::vector<Vec2> step_displacement_;  // free-motion displacement this sub-step
  std::vector<std::uint32_t> to_wake_;
  std::vector<double> sort_keys_;
  std::vector<double> contact_targets_;
  std::vector<double> contact_impulses_;
  std::vector<double> contact_warm_;
  std::vector<std::uint8_t> sleep_ready_;
  std::vector<std::uint32_t> island_parent_;
};

}  // namespace phys
