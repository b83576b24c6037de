#pragma once
// One sub-step of the world, in the classic recipe's order (docs/PHYSICS.md):
//   friction; acceleration and gravity; move on Y, collide on Y; move on X,
//   collide on X; restitution.
// plus what the recipe leaves out and a server needs: a broadphase, swept motion
// against static bodies (nothing tunnels), shock propagation for stacks, and sleep.
// The runner is declared here and defined phase by phase in the step*.cpp files;
// what more than one phase calls in its inner loops is defined here, inline.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "physics/formulas.h"
#include "sweep.h"
#include "world_impl.h"

namespace phys {

class StepRunner {
 public:
  StepRunner(WorldImpl& world, double h)
      : w_(world),
        s_(world.settings),
        h_(h),
        gravity_on_(s_.gravity.x != 0.0 || s_.gravity.y != 0.0),
        up_(gravity_on_ ? -s_.gravity * (1.0 / length(s_.gravity)) : Vec2{0.0, 1.0}),
        rest_speed_(s_.rest_speed > 0.0 ? s_.rest_speed : 2.0 * length(s_.gravity) * h),
        shock_(s_.shock_propagation && gravity_on_),
        hold_(s_.hold_resting_support && gravity_on_),
        speculative_margin_(0.5 * length(s_.gravity) * h * h),
        // (Never, for a limit so large that its square would overflow.)
        surely_slow_(s_.max_speed < 1.0e150 ? (0.5 * s_.max_speed) * (0.5 * s_.max_speed) : -1.0) {}

  void run();

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  // A contact whose normal is within 72.5 degrees of "up" (cosine 0.3) carries weight
  // (supports). At 60 degrees, a circle sunk into a narrow gap between two resting
  // neighbours, meeting them less than 30 degrees above level, was no load of theirs:
  // the passes split its pushes half and half, pressing them apart into their
  // pockets. The frictionless 16,000-circle pile then fell asleep only at 60 s, with
  // rows of side-by-side circles compressed end to end (0.0148 m); at 72.5 degrees it
  // sleeps at 43.5 s with 0.0042 m (docs/PHYSICS.md, "Stacks: shock propagation").
  static constexpr double kSupportCosine = 0.3;
  // A normal this close to gravity's line is a face resting on a face.
  static constexpr double kAlongGravity = 1.0 - 1.0e-9;
  // Time-of-impact stops per body, axis and sub-step (a bounce, then maybe another).
  static constexpr int kMaxHitsPerMove = 4;
  // Candidate boxes grow by this fraction of a body's smaller half extent.
  static constexpr double kPushMargin = 0.1;
  // Pairs are found with boxes grown by this fraction more, and reused while every
  // body stays inside its grown box.
  static constexpr double kFatMargin = 0.1;
  // How many candidate pairs ahead the position passes prefetch scattered bodies.
  static constexpr std::uint32_t kPrefetchAhead = 8;
  // Where a Body's cold line begins (its third cache line: still_time and after).
  static constexpr std::size_t kColdLineOffset = 2 * 64;
  static_assert(offsetof(Body, still_time) >= kColdLineOffset &&
                    offsetof(Body, still_anchor) + sizeof(Vec2) <= 3 * 64,
                "update_sleep prefetches the line of still_time and still_anchor");
  // Up to this many static and sleeping bodies are tested one by one, not through
  // their grid.
  static constexpr std::size_t kFewFixed = 8;

  static double component(const Vec2& v, int axis) { return axis == 0 ? v.x : v.y; }
  static double& component(Vec2& v, int axis) { return axis == 0 ? v.x : v.y; }
  Body& body(std::uint32_t slot) { return w_.bodies[slot]; }
  // The loops over the awake bodies in processing order read them where their
  // slots are: in a pile that has flowed, all over memory, where the hardware's
  // prefetcher cannot follow. Each asks for the body kPrefetchAhead places on.
  void prefetch_ahead(std::size_t p) const {
    if (p + kPrefetchAhead < w_.active_.size()) {
      __builtin_prefetch(&w_.bodies[w_.active_[p + kPrefetchAhead]]);
    }
  }
  // The same, for a loop that reads a body's cold line too (still_time and after).
  void prefetch_ahead_with_cold_line(std::size_t p) const {
    if (p + kPrefetchAhead < w_.active_.size()) {
      const Body* b = &w_.bodies[w_.active_[p + kPrefetchAhead]];
      __builtin_prefetch(b);
      __builtin_prefetch(reinterpret_cast<const char*>(b) + kColdLineOffset);
    }
  }

  // What drives a body: gravity and its own acceleration.
  Vec2 driving_acceleration(const Body& b) const {
    return gravity_on_ ? b.acceleration + s_.gravity : b.acceleration;
  }

  // The acceleration a body moves by: what drives it, less what its contacts held
  // back last sub-step (see Body::held).
  Vec2 moving_acceleration(const Body& b) const {
    return gravity_on_ ? driving_acceleration(b) + b.held : b.acceleration;
  }

  // Shock propagation, for both the position and the velocity passes: a body resting
  // on support (a fixed body below it, or a supported body) is immovable for the
  // bodies it carries, for contacts within 72.5 degrees of vertical. wa and wb are
  // the inverse-mass weights of the pair; the carrier's becomes zero.
  void carry(bool fixed, std::uint32_t lower_pos, std::uint32_t upper_pos, double up, double& wa,
             double& wb) {
    carry(w_.supported_.data(), shock_, fixed, lower_pos, upper_pos, up, wa, wb);
  }
  // The same on a plain array: a loop that passes it keeps it in a register, where
  // the vector's pointer would be reloaded after every byte store (which may alias).
  static void carry(std::uint8_t* supported, bool shock, bool fixed, std::uint32_t lower_pos,
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

  // Two bodies at rest on each other are left a slop apart by the push that
  // separated them. If that pair were no contact in the next step, a column of
  // bodies falling together would have no contact inside it every other step: the
  // velocity pass would stop only its bottom, and the column would breathe by a
  // millimetre and 0.1 m/s a step forever, never asleep. Pairs closer than this
  // margin are resting contacts for the velocity pass, like touching ones (a gap
  // within the slop is closed by no velocity). Circles get a wider margin on top
  // (speculative_margin_).
  double near_miss_margin() const { return 2.0 * s_.slop; }

  // Marks candidate c as a contact with normal n; the restitution phase gathers
  // the marked candidates in candidate order (so no sort is needed).
  void record_contact(std::uint32_t c, Vec2 n) {
    w_.contact_of_candidate_[c] = 1;
    w_.contact_near_miss_[c] = 0;
    w_.contact_normal_[c] = n;
  }

  // The load factor of a contact's friction: for a support contact (within 72.5
  // degrees of vertical), the load of the body on top; 1 for any other.
  static double load_on(bool fixed, const Body& lower, const Body& upper, double up) {
    if (up < -kSupportCosine) return lower.load;
    if (up > kSupportCosine && !fixed) return upper.load;
    return 1.0;
  }
  // How fast a hit must close on a sleeping body to wake it: a resting contact's
  // speed from above (resting_on_it), the sleep speed from the side or below (see
  // wake_if_hit).
  double wake_speed(bool resting_on_it) const {
    return resting_on_it ? rest_speed_ : s_.sleep_speed;
  }

  // Each phase's file defines its helpers `inline`, as they were when the whole runner
  // was one class body: only that file calls them, and the compiler weighs them for
  // inlining into its loops as it did then. The pair tests of the position passes and
  // gather_contact are forced inline: left out of line, a call per pair and per
  // contact made the step a few per cent slower.

  // step.cpp: the order of a sub-step, and the processing order of the bodies
  inline void order_by_height();
  inline void merge_joined();

  // step_integrate.cpp: free motion, and the candidate pairs it can reach
  void integrate();
  template <bool kPrefetch>
  inline void integrate();
  inline Aabb needed_box(const Body& b, Vec2 d) const;
  static inline Aabb fattened(const Body& b, const Aabb& needed);
  void find_candidates();

  // step_moves.cpp: the moves along each axis, swept against fixed bodies
  void move(int axis);
  void move_both_axes();
  template <bool kPrefetch>
  inline void move(int first_axis, int last_axis);
  inline void sweep(std::uint32_t p, Body& b, int axis, AxisPath& path);
  static inline Vec2 touching_normal(const Body& mover, const Body& obstacle, int axis,
                                     double toward);

  // step_position.cpp: the position passes (penetration resolution)
  inline double near_gap(const Body& a, const Body& b) const;
  inline bool near(const Body& a, const Body& b) const;
  template <typename Resolve>
  inline void resolve_passes(Resolve&& resolve);
  template <bool kPrefetch, typename Resolve>
  inline void resolve_passes(Resolve& resolve);
  static inline void prefetch_pair(const Body* bodies, const Candidate& cand);
  template <int axis>
  inline void collide_boxes_on();
  void collide_on_y();
  void collide_on_x();
  inline bool separate(const Candidate& cand, Body& a, Body& b, Vec2 n, double depth);
  inline void hold_by_static_friction(const Candidate& cand, Body& a, Body& b, Vec2 n, double push,
                                      double wa, double wb);
  inline bool may_undo_slide(const Body& body, Vec2 undo) const;
  inline void record_near_miss(const Candidate& cand, Vec2 n, double gap);

  // step_velocity.cpp: the velocity phase (restitution, contact friction, warm start)
  void restitution();
  template <bool kFriction>
  static inline void solve_contacts(std::span<ContactRecord> contacts, Vec2* solver,
                                    std::uint8_t* supported, bool shock, bool first_iteration,
                                    bool& changed);
  template <bool kFixed, bool kFriction>
  static inline void solve_contact(ContactRecord& k, Vec2* solver, std::uint8_t* supported,
                                   bool shock, bool first_iteration, bool& changed);
  inline void gather_contact(std::uint32_t c);
  template <bool kFixed>
  static inline bool apply_contact_friction(ContactRecord& k, Vec2& va, Vec2& vb, double wa,
                                            double wb, double mass);
  inline void update_loads(std::span<const ContactRecord> contacts);
  inline void update_held();
  inline void update_held(std::size_t p, Body& b) const;
  static inline double held_part(double change, double a);
  inline void remember_impulses();
  static inline Vec2 cancelled_velocity(Vec2 v, Vec2 correction, double per_second);
  inline void wake_if_hit(const Candidate& cand, const ContactRecord& contact, double closing);

  // step_contact_events.cpp: what contact events need noted (only when they are on)
  void note_touching_pairs();
  void note_swept_hit(const Body& mover, std::uint32_t mover_slot, int axis, double level,
                      double speed, std::uint32_t obstacle_slot);

  // step_sleep.cpp: the world's bounds, and sleep
  void hold_in_bounds();
  void update_sleep();
  inline void sleep_from_the_bottom(std::vector<std::uint8_t>& asleep);
  inline void sleep_held_groups(std::span<const ContactRecord> contacts,
                                std::vector<std::uint8_t>& asleep);

  WorldImpl& w_;
  const WorldSettings& s_;
  double h_;
  bool gravity_on_;
  Vec2 up_;
  double rest_speed_;
  bool shock_;
  bool hold_;
  // A support a little below a resting body is no contact for the velocity pass
  // beyond the near-miss margin, so shock propagation's marks stop there: in a deep
  // pile, whatever rests above such a gap (a column of 60 circles along a wall)
  // fell freely for steps and was pushed back up by centimetres, never asleep.
  // Gaps up to half what a body falls from rest in one sub-step (g*h*h/2, 1.4 mm
  // at 60 Hz) are speculative contacts instead (Box2D v3's speculative distance),
  // closing at most their gap in a sub-step. Zero without gravity.
  double speculative_margin_;
  bool any_active_box_ = false;
  bool any_active_circle_ = false;
  bool any_contact_friction_ = false;
  bool lanes_ = false;               // this sub-step's velocity iterations run in ContactLanes
  bool order_changed_ = false;       // set by order_by_height()
  bool scattered_ = false;           // the processing order is far from slot order
  bool all_inside_ = false;          // integrate() found every body inside its fat box
  bool fat_made_ = false;            // integrate() made the new fat boxes (next_fat_boxes_)
  std::uint32_t contact_count_ = 0;  // records in use at the front of contacts_
  double surely_slow_;               // squared speeds at or below this are under max_speed
};

}  // namespace phys
